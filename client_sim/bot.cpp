#include "client_sim/bot.hpp"

#include <algorithm>
#include <boost/asio/co_spawn.hpp>
#include <boost/asio/detached.hpp>
#include <boost/asio/redirect_error.hpp>
#include <boost/asio/use_awaitable.hpp>
#include <boost/asio/write.hpp>
#include <limits>

#include "client_sim/fleet.hpp"
#include "client_sim/wire.hpp"
#include "protocol/config_hash.hpp"
#include "protocol/decode.hpp"
#include "protocol/verify.hpp"

namespace arena::bots {

namespace {

using boost::asio::redirect_error;
using boost::asio::use_awaitable;

// Bytes per read: several snapshots of a 64-player world at once; 16 MB for 1000 bots.
constexpr std::size_t read_buffer_bytes = 16 * 1024;
// Receive buffer of a slow-reader bot: the kernel's minimum, about two snapshots.
constexpr int slow_reader_buffer_bytes = 4096;
// A server that stops reading our inputs would make pending_ grow without end.
constexpr std::size_t max_pending_bytes = 1 << 20;

std::string reject_text(const protocol::reject_msg& reject) {
    const char* name = protocol::EnumNameRejectCode(reject.code);
    // A newer server may send a code we do not know: show its number.
    const std::string code = (name != nullptr && *name != '\0')
                                 ? std::string(name)
                                 : "code " + std::to_string(static_cast<unsigned>(reject.code));
    return code + ": " + reject.reason;
}

}  // namespace

bot::bot(fleet& owner, std::uint32_t index, behavior_kind kind, misbehavior mode)
    : fleet_(owner),
      index_(index),
      kind_(kind),
      mode_(mode),
      socket_(owner.io()),
      wake_(owner.io()),
      frames_(protocol::max_server_frame_body),
      read_buffer_(read_buffer_bytes),
      fault_rng_(owner.opts().seed ^ (0xa0761d6478bd642fULL * (std::uint64_t{index} + 1))) {
    outcome_.misbehaving = mode != misbehavior::none;
}

boost::asio::awaitable<void> bot::run() {
    try {
        launched_at_ = clock::now();
        phase_ = phase::connecting;
        boost::system::error_code ec;
        if (mode_ == misbehavior::slow_reader) {
            // A small receive window (set before connecting, when TCP negotiates window
            // scaling), so that only the server's own send buffer stands between the fault
            // and the server noticing it, not megabytes of our autotuned buffer as well.
            socket_.open(fleet_.endpoint().protocol(), ec);
            socket_.set_option(boost::asio::socket_base::receive_buffer_size(slow_reader_buffer_bytes), ec);
        }
        co_await socket_.async_connect(fleet_.endpoint(), redirect_error(use_awaitable, ec));
        if (phase_ == phase::ended) co_return;  // aborted while connecting
        if (ec) {
            end(end_kind::socket_error, "connect: " + ec.message());
            co_return;
        }
        // Inputs are tiny and due now: never let Nagle hold one back for the next.
        socket_.set_option(boost::asio::ip::tcp::no_delay(true), ec);
        phase_ = phase::joining;
        const std::string name = fleet_.opts().name_prefix + "-" + std::to_string(index_);
        queue(protocol::encode_hello(protocol::protocol_version, name, token_for(fleet_.opts(), name),
                                     !fleet_.opts().full_snapshots));
        boost::asio::co_spawn(socket_.get_executor(), writer(), boost::asio::detached);
        co_await reader();
    } catch (const std::exception& e) {
        // Our bug, not the server's; still ends only this bot.
        end(end_kind::protocol_error, std::string("internal error: ") + e.what());
    }
}

boost::asio::awaitable<void> bot::reader() {
    boost::system::error_code ec;
    while (phase_ != phase::ended) {
        const std::size_t n =
            co_await socket_.async_read_some(boost::asio::buffer(read_buffer_), redirect_error(use_awaitable, ec));
        if (phase_ == phase::ended) co_return;
        if (ec == boost::asio::error::eof) {
            end(end_kind::by_server, "server closed the connection without Reject or Bye");
            co_return;
        }
        if (ec) {
            end(end_kind::socket_error, "read: " + ec.message());
            co_return;
        }
        fleet_.count_in(n);
        std::span<const std::uint8_t> data(read_buffer_.data(), n);
        while (!data.empty() && phase_ != phase::ended) {
            data = data.subspan(frames_.feed(data));
            if (frames_.failed()) {
                end(end_kind::protocol_error, "bad frame from the server: " + std::string(frames_.error()));
                co_return;
            }
            if (frames_.has_frame()) {
                handle_frame(frames_.frame());
                frames_.next();
            }
        }
        // The fault: leave every later byte in the kernel's buffers, so that the server's
        // outgoing queue for us grows until it gives up on us.
        if (mode_ == misbehavior::slow_reader && phase_ == phase::playing) co_return;
    }
}

boost::asio::awaitable<void> bot::writer() {
    boost::system::error_code ec;
    while (phase_ != phase::ended) {
        if (pending_.empty()) {
            if (close_after_flush_) {
                end(end_kind::orderly, close_reason_);
                co_return;
            }
            wake_.expires_at(boost::asio::steady_timer::time_point::max());
            co_await wake_.async_wait(redirect_error(use_awaitable, ec));
            continue;  // woken (cancelled) by queue() or end()
        }
        // Everything queued goes out in one write; the two buffers keep their capacity.
        std::swap(pending_, sending_);
        co_await boost::asio::async_write(socket_, boost::asio::buffer(sending_), redirect_error(use_awaitable, ec));
        if (phase_ == phase::ended) co_return;
        if (ec) {
            end(end_kind::socket_error, "write: " + ec.message());
            co_return;
        }
        fleet_.count_out(sending_.size());
        sending_.clear();
    }
}

void bot::queue(std::span<const std::uint8_t> bytes) {
    pending_.insert(pending_.end(), bytes.begin(), bytes.end());
    wake_.cancel();
}

void bot::handle_frame(std::span<const std::uint8_t> frame) {
    message_bytes_ = frame.size();
    const auto verified = protocol::verify_message(frame, protocol::server_frame_limits);
    if (!verified) {
        end(end_kind::protocol_error, "invalid message from the server: " + verified.error);
        return;
    }
    const protocol::Message& message = *verified.value;
    using protocol::Payload;
    const Payload type = message.payload_type();
    if (type == Payload::Welcome && phase_ == phase::joining) return on_welcome(message);
    if (type == Payload::Snapshot && phase_ == phase::playing) return on_snapshot(message);
    if (type == Payload::Pong && phase_ == phase::playing) return on_pong(message);
    if (type == Payload::Reject) return on_reject(message);
    if (type == Payload::Bye) return on_bye(message);
    end(end_kind::protocol_error, "unexpected " + std::string(protocol::payload_name(type)) + " from the server " +
                                      (phase_ == phase::joining ? "before Welcome" : "while playing"));
}

void bot::on_welcome(const protocol::Message& message) {
    const auto welcome = protocol::decode_welcome(message);
    if (!welcome) return end(end_kind::protocol_error, "Welcome: " + welcome.error);
    const protocol::welcome_info& w = welcome.value;
    if (protocol::world_config_hash(w.world_config) != w.world_config_hash)
        return end(end_kind::protocol_error, "Welcome: world_config_hash does not match world_config");
    if (w.world_version != world::world_version)
        return end(end_kind::protocol_error, "Welcome: world_version " + std::to_string(w.world_version) +
                                                 ", this client predicts version " +
                                                 std::to_string(world::world_version));
    if (w.tick_rate == 0 || w.snapshot_rate == 0)
        return end(end_kind::protocol_error, "Welcome: tick_rate and snapshot_rate must be positive");
    std::string error;
    const world::world_config* config = fleet_.config_for(w, error);
    if (config == nullptr) return end(end_kind::protocol_error, "Welcome: world_config: " + error);

    player_id_ = w.player_id;
    entity_id_ = w.entity_id;
    tick_rate_ = w.tick_rate;
    predictor_.emplace(*config, entity_id_, player_id_);
    if (!fleet_.opts().full_snapshots) deltas_.emplace(tick_rate_);
    behavior_.emplace(kind_, fleet_.opts().seed, index_, *config);
    phase_ = phase::playing;
    outcome_.joined = true;
    fleet_.on_joined(w);
}

void bot::on_snapshot(const protocol::Message& message) {
    const auto decoded = protocol::decode_snapshot(message);
    if (!decoded) return end(end_kind::protocol_error, "Snapshot: " + decoded.error);
    const protocol::snapshot_view& snapshot = decoded.value;
    const clock::time_point now = clock::now();
    fleet_metrics& m = fleet_.metrics();
    ++m.snapshots;
    ++m.interval_snapshots;
    if (snapshots_++ == 0) {
        first_snapshot_at_ = now;
    } else if (!outcome_.misbehaving) {
        m.snapshot_gap_ms.add(std::chrono::duration<double, std::milli>(now - last_snapshot_at_).count());
    }
    last_snapshot_at_ = now;
    m.snapshot_bytes_each.add(static_cast<double>(message_bytes_));
    m.snapshot_bytes += message_bytes_;

    std::span<const protocol::BodyState> bodies = snapshot.bodies;
    if (snapshot.is_delta) {
        if (!deltas_) return end(end_kind::protocol_error, "Snapshot: a delta, but this bot asked for full snapshots");
        ++m.delta_snapshots;
        const auto view = deltas_->receive(snapshot);
        if (!view) {
            // The receiver dropped its baselines, so the next ack (0) brings a full view.
            ++m.delta_errors;
            ++m.delta_problems[view.error];
            return;
        }
        m.delta_payload_bytes += snapshot.delta.size();
        m.delta_bodies += view.value.size();
        decoded_.clear();
        for (const protocol::delta::quantized_body& q : view.value) decoded_.push_back(protocol::delta::dequantize(q));
        bodies = decoded_;
    }
    m.bodies_in_view.add(static_cast<double>(bodies.size()));
    m.view_bodies += bodies.size();

    // Bodies come in increasing id order: a binary search, not a scan of every body.
    const auto at = std::lower_bound(bodies.begin(), bodies.end(), entity_id_,
                                     [](const protocol::BodyState& b, std::uint32_t id) { return b.id() < id; });
    const protocol::BodyState* own = (at != bodies.end() && at->id() == entity_id_) ? &*at : nullptr;
    const predictor::correction c = predictor_->on_snapshot(snapshot.ack_sequence, own);
    if (c.problem != predictor::ack_problem::none && !outcome_.misbehaving) {
        return end(end_kind::protocol_error, c.problem == predictor::ack_problem::went_back
                                                 ? "Snapshot: ack_sequence went back"
                                                 : "Snapshot: ack_sequence acknowledges an input never sent");
    }
    if (!outcome_.misbehaving) {
        if (c.error) {
            m.prediction_error_m.add(*c.error);
            if (*c.error == 0.0f) ++m.predictions_exact;
            m.interval_prediction_error_m.add(*c.error);
        }
        m.input_lag_ticks.add(static_cast<double>(predictor_->last_sequence() - snapshot.ack_sequence));
    }
    behavior_->observe(bodies, entity_id_);
}

void bot::on_pong(const protocol::Message& message) {
    const auto pong = protocol::decode_pong(message);
    if (!pong) return end(end_kind::protocol_error, "Pong: " + pong.error);
    const std::uint64_t now = fleet_.now_ns();
    // client_time is ours, echoed; a value from the future is not one we sent.
    if (outcome_.misbehaving || pong.value.client_time > now) return;
    const double rtt_ms = static_cast<double>(now - pong.value.client_time) / 1e6;
    fleet_.metrics().rtt_ms.add(rtt_ms);
    fleet_.metrics().interval_rtt_ms.add(rtt_ms);
}

void bot::on_reject(const protocol::Message& message) {
    const auto reject = protocol::decode_reject(message);
    if (!reject) return end(end_kind::protocol_error, "Reject: " + reject.error);
    const std::string text = reject_text(reject.value);
    ++fleet_.metrics().rejects[text];
    outcome_.server_goodbye = reject.value.code == protocol::RejectCode::shutting_down;
    end(end_kind::by_server, "Reject " + text);
}

void bot::on_bye(const protocol::Message& message) {
    const auto bye = protocol::decode_bye(message);
    if (!bye) return end(end_kind::protocol_error, "Bye: " + bye.error);
    // An orderly goodbye (the server's match is over, or it is stopping), not a fault.
    outcome_.server_goodbye = true;
    end(end_kind::by_server, "Bye: " + bye.value.reason);
}

void bot::on_tick(std::uint64_t tick) {
    if (phase_ != phase::playing || close_after_flush_) return;
    ++ticks_played_;
    if (mode_ != misbehavior::none && ticks_played_ > misbehave_after_ticks && misbehave()) return;
    send_input(behavior_->next({predictor_->body()}));
    // One Ping a second, bots spread over the second so the Pongs do not come in a burst.
    if ((tick + index_) % tick_rate_ == 0) send_ping();
}

void bot::send_input(const world::player_input& input) {
    const std::uint32_t sequence = predictor_->last_sequence() + 1;
    // A NaN input goes to the predictor too (the world skips inputs that fail check_input),
    // so that sequences stay consecutive.
    predictor_->on_input(sequence, input);
    const std::uint32_t snapshot_ack = deltas_ ? deltas_->ack() : 0;
    append_input(fleet_.encoder(), {sequence, input.thrust, input.turn, input.buttons, snapshot_ack}, pending_);
    ++fleet_.metrics().inputs_sent;
    if (pending_.size() > max_pending_bytes) return end(end_kind::socket_error, "server stopped reading our inputs");
    wake_.cancel();
}

void bot::send_ping() {
    append_ping(fleet_.encoder(), fleet_.now_ns(), pending_);
    wake_.cancel();
}

bool bot::misbehave() {
    switch (mode_) {
        case misbehavior::none:
        case misbehavior::slow_reader:  // the reader does it
            return false;
        case misbehavior::flood:
            for (std::uint32_t i = 0; i < flood_inputs_per_tick; ++i) send_input(behavior_->next({predictor_->body()}));
            return true;
        case misbehavior::garbage:
        case misbehavior::oversize:
        case misbehavior::nan:
        case misbehavior::abrupt_close:
            break;
    }
    if (fault_done_) return false;  // done once; play on until the server hangs up
    fault_done_ = true;
    switch (mode_) {
        case misbehavior::garbage:
            queue(garbage_frame(fault_rng_));
            return false;
        case misbehavior::oversize:
            queue(oversize_prefix());
            return false;
        case misbehavior::nan:
            send_input({std::numeric_limits<float>::quiet_NaN(), 0.0f, 0});
            return true;
        case misbehavior::abrupt_close: {
            const std::uint32_t sequence = predictor_->last_sequence() + 1;
            queue(half_frame(protocol::encode_input({sequence, 0.5f, 0.0f, 0})));
            close_after_flush_ = true;
            close_reason_ = "closed mid-frame on purpose (abrupt-close)";
            return true;
        }
        default:
            return false;
    }
}

void bot::finish() {
    if (phase_ == phase::ended) return;
    if (phase_ != phase::playing)
        return end(end_kind::orderly,
                   phase_ == phase::joining ? "no Welcome before the run ended" : "not connected before the run ended");
    if (close_after_flush_) return;
    queue(protocol::encode_bye("run finished"));
    close_after_flush_ = true;
    close_reason_ = "run finished";
}

void bot::abort(const std::string& reason) {
    end(end_kind::socket_error, reason);
}

void bot::check_join_timeout(clock::time_point now) {
    if (phase_ != phase::connecting && phase_ != phase::joining) return;
    if (now - launched_at_ < std::chrono::duration<double>(fleet_.opts().join_timeout)) return;
    end(end_kind::socket_error, phase_ == phase::connecting ? "connect timed out" : "no Welcome in time");
}

void bot::end(end_kind kind, const std::string& reason) {
    if (phase_ == phase::ended) return;
    const bool was_playing = phase_ == phase::playing;
    phase_ = phase::ended;
    outcome_.ended = true;
    outcome_.reason = reason;
    outcome_.ended_early = !fleet_.stopping();
    if (kind == end_kind::protocol_error) outcome_.protocol_error = true;
    if (outcome_.ended_early) ++fleet_.metrics().disconnects[reason];
    boost::system::error_code ignored;
    socket_.shutdown(boost::asio::ip::tcp::socket::shutdown_both, ignored);
    socket_.close(ignored);
    wake_.cancel();
    fleet_.on_bot_ended(was_playing);
}

void bot::add_final_figures(fleet_metrics& m) const {
    if (outcome_.misbehaving || snapshots_ < 2) return;
    const double seconds = std::chrono::duration<double>(last_snapshot_at_ - first_snapshot_at_).count();
    if (seconds > 0) m.snapshots_per_s_per_bot.add(static_cast<double>(snapshots_ - 1) / seconds);
}

}  // namespace arena::bots
