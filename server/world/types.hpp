#pragma once
// The world's one scalar type and its vector.
//
// Why float (not double): the wire carries floats (BodyState), so a float world state is sent
// exactly as it is: a client that resets to a snapshot holds the server's very bits, and its
// prediction with zero latency is exact. Float also halves the bytes the integrator streams
// through memory. Its resolution (about 0.06 mm at 1 km from the origin) is far below what a
// game of this size can show. All arithmetic is IEEE single precision with -ffp-contract=off,
// so it is deterministic across g++/clang++ and optimisation levels.
#include <Eigen/Core>

namespace arena::world {

using real = float;
using vec2 = Eigen::Matrix<real, 2, 1>;

}  // namespace arena::world
