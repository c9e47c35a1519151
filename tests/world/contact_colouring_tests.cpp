// The contacts' colouring (server/world/contact_colouring.hpp): contacts of one colour share no
// moving body, so that a group's lanes can be solved at once; static bodies never count; a body
// in more contacts than there are colours sends the rest to the overflow, one group each.
#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <set>
#include <vector>

#include "server/world/contact_colouring.hpp"
#include "server/world/wide.hpp"

using namespace arena::world;

namespace {

contact between(uint32_t slot_a, uint32_t slot_b) {
    contact c;
    c.slot_a = slot_a;
    c.slot_b = slot_b;
    c.count = 1;
    return c;
}

// Each group's contacts, without the empty lanes.
std::vector<std::vector<uint32_t>> groups_of(const contact_colouring& colouring) {
    std::vector<std::vector<uint32_t>> groups;
    const auto lanes = colouring.lanes();
    for (size_t g = 0; g < colouring.group_count(); ++g) {
        std::vector<uint32_t> group;
        for (size_t i = 0; i < wide_lanes; ++i)
            if (lanes[g * wide_lanes + i] != contact_colouring::no_contact) group.push_back(lanes[g * wide_lanes + i]);
        groups.push_back(group);
    }
    return groups;
}

}  // namespace

TEST_CASE("no two contacts in a group share a moving body, and every contact is in one group", "[world][colouring]") {
    // A chain of 40 bodies (each touching the next) and a fan of 10 contacts against slot 0.
    std::vector<contact> contacts;
    for (uint32_t s = 1; s < 40; ++s) contacts.push_back(between(s, s + 1));
    for (uint32_t s = 1; s <= 10; ++s) contacts.push_back(between(0, s));
    contact_colouring colouring;
    colouring.colour(contacts, 41);
    REQUIRE(colouring.lanes().size() == colouring.group_count() * wide_lanes);
    std::multiset<uint32_t> seen;
    for (const auto& group : groups_of(colouring)) {
        std::set<uint32_t> bodies;
        for (const uint32_t i : group) {
            seen.insert(i);
            for (const uint32_t s : {contacts[i].slot_a, contacts[i].slot_b}) {
                if (s == 0) continue;
                CHECK(bodies.insert(s).second);
            }
        }
    }
    std::multiset<uint32_t> all;
    for (uint32_t i = 0; i < contacts.size(); ++i) all.insert(i);
    CHECK(seen == all);
    // A chain needs two colours; the contacts with slot 0 fit in beside them.
    CHECK(colouring.colours_used() == 3);
    CHECK(colouring.overflow() == 0);
}

TEST_CASE("a colour's contacts keep their order and only its last group is padded", "[world][colouring]") {
    // Ten contacts of disjoint pairs: all colour 0, in contact order.
    std::vector<contact> contacts;
    for (uint32_t k = 0; k < 10; ++k) contacts.push_back(between(2 * k + 1, 2 * k + 2));
    contact_colouring colouring;
    colouring.colour(contacts, 21);
    CHECK(colouring.colours_used() == 1);
    const auto lanes = colouring.lanes();
    REQUIRE(lanes.size() == (10 + wide_lanes - 1) / wide_lanes * wide_lanes);
    for (uint32_t i = 0; i < 10; ++i) CHECK(lanes[i] == i);
    for (size_t i = 10; i < lanes.size(); ++i) CHECK(lanes[i] == contact_colouring::no_contact);
}

TEST_CASE("static bodies and walls never take a colour: every contact with them can be colour 0",
          "[world][colouring]") {
    std::vector<contact> contacts;
    for (uint32_t s = 1; s <= 30; ++s) contacts.push_back(between(s, 0));
    contact_colouring colouring;
    colouring.colour(contacts, 31);
    CHECK(colouring.colours_used() == 1);
    CHECK(colouring.group_count() == (30 + wide_lanes - 1) / wide_lanes);
}

TEST_CASE("a body in more contacts than there are colours sends the rest to the overflow, one group each",
          "[world][colouring]") {
    // Body 1 touches 30 others: each contact needs its own colour.
    const uint32_t others = 30;
    std::vector<contact> contacts;
    for (uint32_t s = 2; s < 2 + others; ++s) contacts.push_back(between(1, s));
    contact_colouring colouring;
    colouring.colour(contacts, 2 + others);
    CHECK(colouring.colours_used() == contact_colouring::colour_count);
    CHECK(colouring.overflow() == others - contact_colouring::colour_count);
    const auto groups = groups_of(colouring);
    REQUIRE(groups.size() == others);
    for (uint32_t g = 0; g < others; ++g) {
        // The colours in order (one contact each here), then the overflow in contact order.
        REQUIRE(groups[g].size() == 1);
        CHECK(groups[g][0] == g);
    }
}

TEST_CASE("colouring the same contacts twice gives the same lanes", "[world][colouring][determinism]") {
    std::vector<contact> contacts;
    for (uint32_t k = 0; k < 200; ++k) contacts.push_back(between(1 + (k * 7) % 50, 1 + (k * 13 + 5) % 50));
    contacts.erase(
        std::remove_if(contacts.begin(), contacts.end(), [](const contact& c) { return c.slot_a == c.slot_b; }),
        contacts.end());
    contact_colouring first, second;
    first.colour(contacts, 51);
    second.colour(contacts, 51);
    CHECK(std::equal(first.lanes().begin(), first.lanes().end(), second.lanes().begin(), second.lanes().end()));
}
