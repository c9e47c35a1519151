#include "server/match/outbox.hpp"

namespace arena::match {

void outbox::send(connection& to, protocol::frame_bytes frame) {
    items_.push_back({&to, kind::control, std::move(frame)});
}

void outbox::send_snapshot(connection& to, const protocol::snapshot_encoder& snapshot, uint32_t ack_sequence) {
    const auto frame = snapshot.frame_with_ack(ack_sequence);
    items_.push_back({&to, kind::snapshot, protocol::frame_bytes(frame.begin(), frame.end())});
}

void outbox::send_snapshot_frame(connection& to, std::span<const uint8_t> frame) {
    items_.push_back({&to, kind::snapshot, protocol::frame_bytes(frame.begin(), frame.end())});
}

void outbox::close(connection& to, protocol::RejectCode code, std::string_view reason) {
    items_.push_back({&to, kind::close, {}, code, std::string(reason)});
}

void outbox::deliver() {
    // Taken out first: a delivery may end a connection, whose transport tells the match,
    // which must find an empty outbox if it says anything more.
    std::vector<item> items = std::exchange(items_, {});
    for (item& i : items) {
        switch (i.what) {
            case kind::control:
                i.to->send(std::move(i.bytes));
                break;
            case kind::snapshot:
                i.to->send_snapshot_frame(i.bytes);
                break;
            case kind::close:
                i.to->close(i.code, i.reason);
                break;
        }
    }
}

}  // namespace arena::match
