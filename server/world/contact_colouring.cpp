#include "server/world/contact_colouring.hpp"

#include <array>
#include <bit>

#include "server/world/wide.hpp"

namespace arena::world {

void contact_colouring::colour(std::span<const contact> contacts, size_t slot_count) {
    static_assert(colour_count <= 32, "a slot's colours are the bits of a uint32_t");
    used_.assign(slot_count, 0);
    colour_of_.resize(contacts.size());
    std::array<size_t, colour_count + 1> count{};
    for (size_t i = 0; i < contacts.size(); ++i) {
        const contact& c = contacts[i];
        const uint32_t taken = (c.slot_a ? used_[c.slot_a] : 0u) | (c.slot_b ? used_[c.slot_b] : 0u);
        const auto colour = static_cast<uint32_t>(std::countr_one(taken));
        if (colour >= colour_count) {
            colour_of_[i] = colour_count;
            ++count[colour_count];
            continue;
        }
        const uint32_t bit = 1u << colour;
        if (c.slot_a) used_[c.slot_a] |= bit;
        if (c.slot_b) used_[c.slot_b] |= bit;
        colour_of_[i] = static_cast<uint8_t>(colour);
        ++count[colour];
    }
    // Where each colour's groups start: its contacts rounded up to whole groups; the overflow
    // takes one group per contact.
    std::array<size_t, colour_count + 1> next{};
    size_t total = 0;
    colours_used_ = 0;
    for (uint32_t colour = 0; colour < colour_count; ++colour) {
        next[colour] = total;
        total += (count[colour] + wide_lanes - 1) / wide_lanes * wide_lanes;
        if (count[colour] > 0) colours_used_ = colour + 1;
    }
    next[colour_count] = total;
    overflow_ = count[colour_count];
    total += overflow_ * wide_lanes;
    lanes_.assign(total, no_contact);
    for (size_t i = 0; i < contacts.size(); ++i) {
        const uint32_t colour = colour_of_[i];
        lanes_[next[colour]] = static_cast<uint32_t>(i);
        next[colour] += colour == colour_count ? wide_lanes : 1;
    }
}

size_t contact_colouring::group_count() const {
    return lanes_.size() / wide_lanes;
}

}  // namespace arena::world
