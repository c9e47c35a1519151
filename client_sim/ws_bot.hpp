#pragma once
// One simulated player over WebSocket (the server's --http-port, path /ws): the third I/O
// adapter around a client_core, on Boost.Beast's websocket client. Each frame the core queues
// goes out as one binary message, and each message from the server is one frame for
// client_core::on_frame, as a browser client does it. A reader and a writer coroutine, like the
// TCP bot; Beast stays in ws_bot.cpp (it is heavy to compile).
#include <boost/asio/awaitable.hpp>
#include <cstdint>
#include <memory>
#include <string>

#include "client_sim/bot_session.hpp"
#include "client_sim/client_core.hpp"

namespace arena::bots {

class fleet;

class ws_bot : public bot_session {
public:
    ws_bot(fleet& owner, client_params params);
    ~ws_bot() override;

    boost::asio::awaitable<void> run() override;

private:
    struct io;  // the Beast stream and the writer's wake-up, in ws_bot.cpp

    boost::asio::awaitable<void> reader();
    boost::asio::awaitable<void> writer();
    // After every call into the core: close the stream if it ended, else wake the writer.
    void sync() override;

    fleet& fleet_;
    bool closed_ = false;
    bool open_ = false;  // the upgrade succeeded
    std::unique_ptr<io> io_;
};

}  // namespace arena::bots
