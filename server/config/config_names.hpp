#pragma once
// The JSON names of a world config's enumerations, for the reader (config_json.cpp) and the
// writer (config_to_json.cpp): one table each, so that what is written reads back.
#include <utility>

#include "server/world/config.hpp"

namespace arena::config::names {

inline constexpr std::pair<const char*, world::integrator> integrator_names[] = {
    {"semi-implicit", world::integrator::semi_implicit}, {"explicit", world::integrator::explicit_euler}};
inline constexpr std::pair<const char*, world::boundary> boundary_names[] = {{"open", world::boundary::open},
                                                                             {"wrap", world::boundary::wrap},
                                                                             {"walls", world::boundary::walls},
                                                                             {"floor", world::boundary::floor}};
inline constexpr std::pair<const char*, world::shape_type> shape_names[] = {
    {"circle", world::shape_type::circle},   {"capsule", world::shape_type::capsule},
    {"box", world::shape_type::box},         {"polygon", world::shape_type::polygon},
    {"segment", world::shape_type::segment}, {"chain", world::shape_type::chain}};

}  // namespace arena::config::names
