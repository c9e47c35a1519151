#pragma once
// The match logs through a logger it was handed: one formatted line per event to a sink the
// caller chooses (the server's stderr log with its timestamps, a test's vector, or nothing).
// The match itself neither reads a clock nor touches a stream.
#include <functional>
#include <string_view>

namespace arena::match {

class logger {
public:
    using sink = std::function<void(std::string_view line)>;

    logger() = default;  // silent
    explicit logger(sink to) : sink_(std::move(to)) {}

    // printf-style: one line, without its newline; longer than 1 KiB is cut.
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    void
    operator()(const char* format, ...) const;

    [[nodiscard]] bool enabled() const {
        return static_cast<bool>(sink_);
    }

private:
    sink sink_;
};

}  // namespace arena::match
