// arena-bots: simulated players for an Arena server. Wiring only: options, one io_context on
// this thread, the fleet, the report. See README.md beside this file.
#include <boost/asio/co_spawn.hpp>
#include <boost/asio/io_context.hpp>
#include <cstdio>
#include <exception>
#include <fstream>

#include "client_sim/fleet.hpp"
#include "client_sim/options.hpp"
#include "client_sim/report.hpp"

int main(int argc, char** argv) {
    using namespace arena::bots;
    options opts;
    if (const int code = parse_options(argc, argv, opts); code >= 0) return code;

    // One thread runs everything: a concurrency hint of 1 lets Asio skip its locking.
    boost::asio::io_context io(1);
    fleet bots(io, opts);
    bool crashed = false;
    boost::asio::co_spawn(io, bots.run(), [&crashed](std::exception_ptr e) {
        if (!e) return;
        crashed = true;
        try {
            std::rethrow_exception(e);
        } catch (const std::exception& ex) {
            std::fprintf(stderr, "arena-bots: %s\n", ex.what());
        }
    });
    io.run();

    final_report report = bots.report();
    if (crashed) report.exit_code = 1;
    std::printf("%s", summary_table(report).c_str());
    std::fflush(stdout);
    if (!opts.json.empty()) {
        std::ofstream out(opts.json);
        out << to_json(report).dump(2) << '\n';
        if (!out) {
            std::fprintf(stderr, "arena-bots: cannot write %s\n", opts.json.c_str());
            return 1;
        }
    }
    return report.exit_code;
}
