#include "games/asteroids/asteroids_rules.hpp"

#include <algorithm>
#include <cmath>

#include "server/world/broadphase.hpp"
#include "server/world/trig.hpp"

namespace arena::rules {

using world::real;
using world::vec2;

namespace {

// The rules keep body ids as numbers; the world removes typed ids (server/world/ids.hpp).
void remove_bodies(world::world& w, const std::vector<uint32_t>& ids) {
    std::vector<world::body_id> typed;
    typed.reserve(ids.size());
    for (const uint32_t id : ids) typed.emplace_back(id);
    w.remove_bodies(typed);
}

// 1/√2: a piece of half the area has 1/√2 of the radius.
constexpr real half_area_scale = 0.70710678f;

// Keeps a ship's rng apart from anything else seeded by the world's hash.
constexpr uint64_t rng_salt = 0x61737465726f6964ULL;  // "asteroid"

// The judged_in_past event of `shooter`'s hit on `rewound`, for its ?debug=lag: in mm, as the
// event's values are integers (rounding a float is exact on every target; an open world's far
// body is clamped within int32).
declared_event judged_event(uint32_t shooter, const hit_history::target& rewound) {
    const auto mm = [](real v) {
        return static_cast<int32_t>(std::llround(std::clamp(v * 1000.0f, -2e9f, 2e9f)));
    };
    return {judged_in_past,
            {static_cast<int32_t>(shooter), mm(rewound.position.x()), mm(rewound.position.y()), mm(rewound.radius)}};
}

}  // namespace

asteroids_rules::asteroids_rules(world::world& w, const asteroids_params& params)
    : params_(params), rng_(w.hash() ^ rng_salt) {
    for (const world::body& b : w.bodies())
        if (!b.is_static() && b.owner == 0) rocks_[b.id] = 3;
    wave_size_ = static_cast<uint32_t>(rocks_.size());
    w.set_contact_events(true);
}

void asteroids_rules::make_ship(world::world& w, uint32_t player_id, player& p, uint32_t body_id, bool invulnerable) {
    p.ship = body_id;
    p.last_ship = body_id;
    p.state = ship_state::playing;
    p.vulnerable_at = invulnerable ? w.tick() + params_.invulnerable_ticks : w.tick();
    world::body* b = w.find(body_id);
    if (!b) return;
    // Its own bullets share its negative group: they never touch it.
    b->filter = {category_ship, invulnerable ? 0u : ~0u, -static_cast<int32_t>(player_id)};
}

void asteroids_rules::on_joins(world::world& w, std::span<const uint32_t> owners, std::span<const uint32_t> bodies) {
    for (size_t k = 0; k < owners.size() && k < bodies.size(); ++k) {
        if (bodies[k] == 0) continue;
        player& p = players_[owners[k]];
        p.lives = params_.lives;
        p.score.player = owners[k];
        // A ship that joins beside a rock gets the respawn's grace too.
        make_ship(w, owners[k], p, bodies[k], true);
    }
}

void asteroids_rules::on_leaves(world::world& w, std::span<const uint32_t> bodies) {
    if (bodies.empty()) return;
    // One pass over the players against the sorted leaves: a tick of many leaves stays linear.
    std::vector<uint32_t> leaving(bodies.begin(), bodies.end());
    std::sort(leaving.begin(), leaving.end());
    std::vector<uint32_t> gone;  // player ids, increasing
    for (auto& [player_id, p] : players_) {
        if (p.state == ship_state::out || !std::binary_search(leaving.begin(), leaving.end(), p.last_ship)) continue;
        p.state = ship_state::out;
        p.ship = 0;
        gone.push_back(player_id);
    }
    // Their bullets go with them (the match removes the ships themselves).
    std::vector<uint32_t> removals;
    for (auto it = bullets_.begin(); it != bullets_.end();) {
        if (std::binary_search(gone.begin(), gone.end(), it->second.owner)) {
            removals.push_back(it->first);
            it = bullets_.erase(it);
        } else {
            ++it;
        }
    }
    remove_bodies(w, removals);
}

void asteroids_rules::before_step(world::world& w, const world::tick_inputs& inputs) {
    // In body id order, whatever order the caller listed them in.
    std::vector<std::pair<uint32_t, uint16_t>> firing;  // (body, the input's rewind)
    for (const world::body_input& in : inputs)
        if (in.input.buttons & button_fire) firing.emplace_back(in.body_id.value(), in.input.rewind);
    std::sort(firing.begin(), firing.end());
    for (const auto& [id, rewind] : firing) {
        const world::body* b = w.find(id);
        if (!b) continue;
        auto it = players_.find(b->owner);
        if (it == players_.end() || it->second.ship != id) continue;
        fire(w, it->first, it->second, rewind);
    }
}

void asteroids_rules::fire(world::world& w, uint32_t player_id, player& p, uint16_t rewind) {
    uint32_t live = 0;
    for (const auto& [id, bl] : bullets_) live += bl.owner == player_id ? 1 : 0;
    if (!may_fire(w.tick(), p.next_fire, live, params_)) return;
    world::body* ship = w.find(p.ship);
    if (!ship) return;
    shot s = make_shot(*ship, player_id, params_);
    ship->apply_impulse(s.recoil);  // `ship` may move in memory once the bullet is added
    // A rewound bullet touches nothing of the present: the rules judge it against the past.
    if (rewind != 0) s.bullet.filter.mask = 0;
    const std::optional<uint32_t> id = w.add_body(s.bullet);
    if (!id) return;
    bullets_[*id] = {player_id,
                     w.tick() + params_.bullet_lifetime_ticks,
                     {player_id, s.bullet.position, s.bullet.velocity},
                     rewind,
                     s.bullet.position};
    p.next_fire = w.tick() + params_.fire_cooldown_ticks;
    ++p.score.shots;
}

asteroids_rules::player* asteroids_rules::player_of_ship(uint32_t body_id) {
    for (auto& [id, p] : players_)
        if (p.ship == body_id && p.state == ship_state::playing) return &p;
    return nullptr;
}

void asteroids_rules::destroy_ship(world::world& w, uint32_t player_id, uint32_t shooter,
                                   std::vector<uint32_t>& removals) {
    player& p = players_[player_id];
    events_.push_back({event_kind::ship_destroyed, 0, player_id, shooter, p.ship, shooter ? params_.score_ship : 0});
    removals.push_back(p.ship);
    p.ship = 0;
    ++p.score.deaths;
    // `lives` counts the ships to come: the death after the last one ends the player's play.
    if (p.lives > 0) {
        --p.lives;
        p.state = ship_state::respawning;
        p.respawn_at = w.tick() + params_.respawn_ticks;
    } else {
        p.state = ship_state::out;
    }
}

void asteroids_rules::split_rock(world::world& w, uint32_t id, std::vector<uint32_t>& removals) {
    const uint32_t size = rocks_[id];
    rocks_.erase(id);
    removals.push_back(id);
    const world::body* rock = w.find(id);
    if (size <= 1 || !rock) return;
    const world::body r = *rock;  // add_body moves the bodies
    const world::shape parent = w.shape_of(r);
    world::shape piece_shape = world::make_circle(parent.radius * half_area_scale);
    if (parent.kind != world::shape_kind::circle) {
        std::vector<vec2> corners;
        for (uint8_t k = 0; k < parent.count; ++k) corners.push_back(parent.vertices[k] * half_area_scale);
        const auto made = world::make_polygon(corners, parent.radius * half_area_scale);
        if (made) piece_shape = made.value.geometry;
    }
    world::body_material m;
    m.mass = r.mass * 0.5f;
    m.restitution = r.restitution;
    m.friction = r.friction;
    m.drag_area = r.drag_area * half_area_scale;
    // Across the rock's velocity (or across x for a rock at rest), one piece each way.
    const real speed2 = r.velocity.squaredNorm();
    vec2 across{0, 1};
    if (speed2 > 0) across = vec2{-r.velocity.y(), r.velocity.x()} / std::sqrt(speed2);
    for (const real side : {1.0f, -1.0f}) {
        world::body piece = world::make_body(m, piece_shape, r.position);
        const vec2 offset = across * (side * piece.radius);
        piece.position = r.position + offset;
        piece.angle = r.angle;
        piece.angular_velocity = r.angular_velocity;
        piece.velocity = r.velocity;
        piece.apply_impulse(across * (side * params_.split_impulse));
        const std::optional<uint32_t> made = w.add_body(piece, piece_shape);
        if (made) rocks_[*made] = size - 1;
    }
}

void asteroids_rules::after_step(world::world& w) {
    events_.clear();
    judged_.clear();
    std::vector<uint32_t> removals;
    std::vector<uint32_t> consumed;  // bodies an earlier event of this step used up
    const auto used = [&consumed](uint32_t id) {
        return std::find(consumed.begin(), consumed.end(), id) != consumed.end();
    };
    const auto points = [this](uint32_t size) {
        return size >= 3 ? params_.score_large : size == 2 ? params_.score_medium : params_.score_small;
    };
    // A bullet that hit `target`: its shooter scores and counts a hit, and both are used up.
    const auto bullet_hits = [&](uint32_t bullet, uint32_t target, uint32_t score) -> score_line& {
        score_line& shooter = players_[bullets_[bullet].owner].score;
        shooter.score += score;
        ++shooter.hits;
        bullets_.erase(bullet);
        removals.push_back(bullet);
        consumed.push_back(bullet);
        consumed.push_back(target);
        return shooter;
    };
    for (const world::contact_event& e : w.contact_events()) {
        if (used(e.a) || used(e.b)) continue;
        uint32_t bullet = 0, rock = 0, ship = 0;
        for (const uint32_t id : {e.a, e.b}) {
            if (bullets_.count(id))
                bullet = id;
            else if (rocks_.count(id))
                rock = id;
            else if (player_of_ship(id))
                ship = id;
        }
        if (bullet && rock) {
            const uint32_t size = rocks_[rock];
            events_.push_back(
                {event_kind::rock_hit, static_cast<uint8_t>(size), bullets_[bullet].owner, 0, rock, points(size)});
            bullet_hits(bullet, rock, points(size));
            split_rock(w, rock, removals);
        } else if (bullet && ship) {
            const uint32_t victim = w.find(ship)->owner;
            const uint32_t shooter = bullets_[bullet].owner;
            ++bullet_hits(bullet, ship, params_.score_ship).kills;
            destroy_ship(w, victim, shooter, removals);
        } else if (rock && ship) {
            consumed.push_back(ship);
            destroy_ship(w, w.find(ship)->owner, 0, removals);
        }
    }
    record_targets(w);
    judge_rewound(w, [&](uint32_t bullet, const hit_history::target& rewound) {
        const uint32_t target = rewound.id;
        if (used(bullet) || used(target)) return;
        const auto rock = rocks_.find(target);
        // A target of the past may be gone from the present: then nothing is hit, nor told.
        if (rock == rocks_.end() && player_of_ship(target) == nullptr) return;
        judged_.push_back(judged_event(bullets_[bullet].owner, rewound));
        if (rock != rocks_.end()) {
            const uint32_t size = rock->second;
            events_.push_back(
                {event_kind::rock_hit, static_cast<uint8_t>(size), bullets_[bullet].owner, 0, target, points(size)});
            bullet_hits(bullet, target, points(size));
            split_rock(w, target, removals);
        } else {
            const uint32_t victim = w.find(target)->owner;
            const uint32_t shooter = bullets_[bullet].owner;
            // The victim hears how far back it was hit: it may have seen itself clear by then.
            events_.push_back({event_kind::shot_rewound, 0, victim, shooter, target, bullets_[bullet].rewind});
            ++bullet_hits(bullet, target, params_.score_ship).kills;
            destroy_ship(w, victim, shooter, removals);
        }
    });
    const uint32_t now = w.tick();
    for (auto it = bullets_.begin(); it != bullets_.end();) {
        if (it->second.expires <= now) {
            removals.push_back(it->first);
            it = bullets_.erase(it);
        } else {
            ++it;
        }
    }
    remove_bodies(w, removals);
    for (auto& [id, p] : players_) {
        if (p.state != ship_state::playing || p.vulnerable_at != now) continue;
        if (world::body* b = w.find(p.ship)) b->filter.mask = ~0u;
    }
    respawn_due(w);
    if (rocks_.empty()) spawn_wave(w);
}

void asteroids_rules::record_targets(const world::world& w) {
    std::vector<hit_history::target> targets;
    for (const world::body& b : w.bodies()) {
        const bool rock = rocks_.count(b.id) != 0;
        const bool ship = !rock && (b.filter.category & category_ship) && (b.filter.mask & category_bullet) &&
                          player_of_ship(b.id) != nullptr;
        if (rock || ship) targets.push_back({b.id, b.position, b.radius});
    }
    history_.record(w.tick(), std::move(targets), w.config());  // bodies are in id order
}

template <class Hit>
void asteroids_rules::judge_rewound(const world::world& w, Hit&& hit) {
    std::vector<std::pair<uint32_t, hit_history::target>> hits;  // judged before any is applied
    for (auto& [id, b] : bullets_) {
        if (b.rewind == 0) continue;
        const world::body* bullet = w.find(id);
        if (bullet == nullptr) continue;
        const world::vec2 from = b.last_position;  // a copy: a lambda cannot capture a structured binding
        const world::vec2 step = world::displacement(from, bullet->position, w.config());
        const world::body* own = w.find(players_[b.owner].ship);
        hit_history::target nearest;
        world::real nearest_along = 2;
        const world::vec2 middle = from + step * 0.5f;
        const world::real reach = step.norm() * 0.5f + bullet->radius;
        history_.rewound_near(w.tick(), b.rewind, middle, reach, w.config(), [&](const hit_history::target& t) {
            if (own != nullptr && t.id == own->id) return;  // never its own ship
            const auto along = sweep_hits(from, step, t.position, t.radius + bullet->radius, w.config());
            // Along the sweep: the first target in the bullet's way is the one it hits.
            if (along && *along < nearest_along) {
                nearest_along = *along;
                nearest = t;
            }
        });
        b.last_position = bullet->position;
        if (nearest.id != 0) hits.emplace_back(id, nearest);
    }
    for (const auto& [bullet, target] : hits) hit(bullet, target);
}

void asteroids_rules::respawn_due(world::world& w) {
    for (auto& [id, p] : players_) {
        if (p.state != ship_state::respawning || p.respawn_at > w.tick()) continue;
        const world::body_material& m = w.config().player;
        world::body b = world::make_body(m, free_spot(w, m.radius, params_.spawn_clearance));
        b.owner = id;
        const std::optional<uint32_t> ship = w.add_body(b);
        if (!ship) continue;  // the world is full: try again next tick
        make_ship(w, id, p, *ship, true);
        events_.push_back({event_kind::respawn, 0, id, 0, *ship, 0});
    }
}

void asteroids_rules::spawn_wave(world::world& w) {
    ++wave_size_;
    events_.push_back({event_kind::wave, 0, 0, 0, 0, wave_size_});
    const world::rock_config& rocks = w.config().rocks;
    const uint32_t corners_per_rock = std::clamp<uint32_t>(rocks.polygon_vertices, 3, world::max_polygon_vertices);
    const real radius = params_.wave_rock_radius;
    for (uint32_t k = 0; k < wave_size_; ++k) {
        const vec2 at = free_spot(w, radius, params_.spawn_clearance);
        std::vector<vec2> corners;
        for (uint32_t c = 0; c < corners_per_rock; ++c) {
            const real distance = radius * rng_.uniform(0.6f, 1.0f);
            const world::cos_sin dir =
                world::compute_cos_sin(2 * world::pi * static_cast<real>(c) / static_cast<real>(corners_per_rock));
            corners.push_back(vec2{dir.c, dir.s} * distance);
        }
        // One draw per statement: argument evaluation order differs between compilers.
        const real vx = rng_.uniform(-rocks.max_speed, rocks.max_speed);
        const real vy = rng_.uniform(-rocks.max_speed, rocks.max_speed);
        const auto made = world::make_polygon(corners);
        const world::shape s = made ? made.value.geometry : world::make_circle(radius);
        world::body b = world::make_body(rocks.material, s, at);
        b.velocity = {vx, vy};
        const std::optional<uint32_t> id = w.add_body(b, s);
        if (id) rocks_[*id] = 3;
    }
}

vec2 asteroids_rules::free_spot(const world::world& w, real radius, real clearance) {
    const world::world_config& c = w.config();
    const vec2 lo{radius, radius};
    const vec2 hi = (c.size - lo).cwiseMax(lo);
    vec2 p{0, 0};
    for (int attempt = 0; attempt < 32; ++attempt) {
        const real x = rng_.uniform(lo.x(), hi.x());
        const real y = rng_.uniform(lo.y(), hi.y());
        p = {x, y};
        bool free = true;
        for (const world::body& b : w.bodies()) {
            const real reach = b.radius + radius + clearance;
            if (world::displacement(p, b.position, c).squaredNorm() < reach * reach) {
                free = false;
                break;
            }
        }
        if (free) break;
    }
    return p;
}

uint32_t asteroids_rules::body_of(uint32_t player) const {
    const auto it = players_.find(player);
    return it == players_.end() ? 0 : it->second.ship;
}

uint8_t asteroids_rules::kind_of(uint32_t body_id) const {
    if (rocks_.count(body_id)) return kind_rock;
    if (bullets_.count(body_id)) return kind_bullet;
    for (const auto& [id, p] : players_)
        if (p.ship == body_id) return kind_ship;
    return 0;
}

uint8_t asteroids_rules::snapshot_weight(uint8_t kind) const {
    switch (kind) {
        case kind_ship:
            return 4;
        case kind_bullet:
            return 3;
        case kind_rock:
            return 1;
        default:
            return 2;
    }
}

uint32_t asteroids_rules::rock_size(uint32_t id) const {
    const auto it = rocks_.find(id);
    return it == rocks_.end() ? 0 : it->second;
}

const shot_record* asteroids_rules::shot_of(uint32_t body_id) const {
    const auto it = bullets_.find(body_id);
    return it == bullets_.end() ? nullptr : &it->second.spawned;
}

uint32_t asteroids_rules::bullet_owner(uint32_t id) const {
    const auto it = bullets_.find(id);
    return it == bullets_.end() ? 0 : it->second.owner;
}

bool asteroids_rules::invulnerable(const world::world& w, uint32_t player) const {
    const auto it = players_.find(player);
    if (it == players_.end() || it->second.state != ship_state::playing) return false;
    const world::body* b = w.find(it->second.ship);
    return b && b->filter.mask == 0;
}

void asteroids_rules::hash(world::fnv1a& h) const {
    h.add_u64(rng_.state());
    h.add_u32(wave_size_);
    h.add_u32(static_cast<uint32_t>(players_.size()));
    for (const auto& [id, p] : players_) {
        h.add_u32(id);
        h.add_u32(p.ship);
        h.add_u32(p.last_ship);
        h.add_u8(static_cast<uint8_t>(p.state));
        h.add_u32(p.lives);
        h.add_u32(p.respawn_at);
        h.add_u32(p.vulnerable_at);
        h.add_u32(p.next_fire);
        h.add_u32(p.score.score);
        h.add_u32(p.score.kills);
        h.add_u32(p.score.deaths);
        h.add_u32(p.score.shots);
        h.add_u32(p.score.hits);
    }
    h.add_u32(static_cast<uint32_t>(bullets_.size()));
    for (const auto& [id, b] : bullets_) {
        h.add_u32(id);
        h.add_u32(b.owner);
        h.add_u32(b.expires);
        if (b.rewind != 0) h.add_u32(b.rewind);  // only then: recordings of before keep their hashes
    }
    h.add_u32(static_cast<uint32_t>(rocks_.size()));
    for (const auto& [id, size] : rocks_) {
        h.add_u32(id);
        h.add_u32(size);
    }
}

std::vector<score_line> asteroids_rules::scoreboard() const {
    std::vector<score_line> lines;
    for (const auto& [id, p] : players_) {
        score_line s = p.score;
        s.player = id;
        s.lives = p.lives;
        s.out = p.state == ship_state::out;
        s.state = p.state;
        lines.push_back(s);
    }
    return lines;
}

protocol::game_manifest asteroids_rules::manifest() const {
    protocol::game_manifest m;
    m.name = "asteroids";
    // No fields of its own: the protocol's PlayerLine is Asteroids' scoreboard (score, kills,
    // deaths, shots, hits, lives, state), and its GameEvent kinds are Asteroids' events. Declaring
    // them again would send every change twice.
    m.body_tags = {{kind_ship, "ship", "ship", ""}, {kind_rock, "rock", "", ""}, {kind_bullet, "bullet", "disc", ""}};
    m.inputs = {{"fire", 1, "Space"}, {"boost", 0, "ShiftLeft"}};
    // Told without words (no message): a page draws it under ?debug=lag.
    m.events = {{"judged_in_past", {"player", "x_mm", "y_mm", "radius_mm"}, ""}};
    return m;
}

uint32_t asteroids_rules::winner() const {
    uint32_t best = 0, best_score = 0;
    bool tie = false;
    for (const auto& [id, p] : players_) {
        if (best == 0 || p.score.score > best_score) {
            best = id;
            best_score = p.score.score;
            tie = false;
        } else if (p.score.score == best_score) {
            tie = true;
        }
    }
    return tie ? 0 : best;
}

}  // namespace arena::rules
