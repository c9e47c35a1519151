#include "server/world/trig.hpp"

namespace arena::world {

namespace {

// Taylor polynomials on [−π/4, π/4], evaluated in double (exact ×,+ under IEEE, no FMA since
// -ffp-contract=off) and rounded once to float: error below float's half-ulp on that range.
double sin_poly(double x) {
    const double x2 = x * x;
    return x * (1.0 +
                x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 * (1.0 / 362880 + x2 * (-1.0 / 39916800))))));
}

double cos_poly(double x) {
    const double x2 = x * x;
    return 1.0 +
           x2 * (-0.5 + x2 * (1.0 / 24 +
                              x2 * (-1.0 / 720 + x2 * (1.0 / 40320 + x2 * (-1.0 / 3628800 + x2 * (1.0 / 479001600))))));
}

}  // namespace

cos_sin compute_cos_sin(real angle) {
    const double a = static_cast<double>(wrap_angle(angle));
    // Reduce to [−π/4, π/4] by quarter turns: a = q·π/2 + r.
    const double half_pi = 1.57079632679489661923;
    const double scaled = a / half_pi;
    const long long q = static_cast<long long>(scaled >= 0 ? scaled + 0.5 : scaled - 0.5);
    const double r = a - static_cast<double>(q) * half_pi;
    const double s = sin_poly(r);
    const double c = cos_poly(r);
    switch (((q % 4) + 4) % 4) {
        case 0:
            return {static_cast<real>(c), static_cast<real>(s)};
        case 1:
            return {static_cast<real>(-s), static_cast<real>(c)};
        case 2:
            return {static_cast<real>(-c), static_cast<real>(-s)};
        default:
            return {static_cast<real>(s), static_cast<real>(-c)};
    }
}

}  // namespace arena::world
