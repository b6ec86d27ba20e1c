#pragma once
// Step 3.5: re-move by the bending feature, eqs. (1)-(13), one fiber at a time.
//
// Units: r (fiber radius) m, E_f (fiber modulus) Pa, so k r^4 is N m^2, and so
// are the bending feature F = k r^4 theta^2 (eqs. (1)-(2), theta the turning
// angle in rad) and E_row (eq. (11)).
//
// Interpretation of eq. (13): e = k' (c - L)^2 with k' = k_prime * h, h the rest
// spacing and k_prime in N/m (e is an E, N m^2: k_prime h (c - L)^2 is N/m x m x
// m^2; the balance below says the same, 1/m^2 = N/m x m / N m^2): with F ~ k r^4 h curvature^2 per
// node, E_row ~ k r^4 h * integral(curvature^2), and the balance E = e then
// reads (m pi / c)^2 = k_prime dL / (2 k r^4), the same at any resolution
// (../shared/paper/README.md derives it for a wave of m half-waves, chord c,
// slack dL = L - c).
//
// Interpretation of Fig. 8 (the figure is not in the text): scaling a row's
// bulge cannot move E toward e once 3.3-3.4 hold the lengths; only the number
// of waves can. So when |E - e| > tolerance * max(E, e), the fiber is re-laid,
// in the plane of its chord and the cloth's normal, on the wave of m half-waves
// nearest the balance, m = round((c/pi) sqrt(k_prime dL / (2 k r^4))) >= 1,
// and at most segments/4 (a finer wave would be a zigzag of the lattice),
// with the amplitude that keeps its length (the discrete wave's polyline length
// equals the rest length; about (2c / (m pi)) sqrt(dL / c) for small slopes) and
// the sign that best matches its present shape. A fiber without slack is laid
// straight. Thick fibers (large r) balance with few broad waves and thin ones
// with many fine ones: wavelength 2c/m grows as r^2 (property 3).
//
// The tolerance of the paper's stop test defaults to 0: every fiber is re-laid
// on every pass. The re-lay depends only on the chord, the slack and the sign,
// so with the corners held it gives back the same shape: a formed wrinkle
// persists exactly (property 2; measured 0 mm over 100 held frames). A positive
// tolerance leaves near-balanced fibers as they are, and then neighbours that
// crossed the threshold on different frames disagree on their wave count: in
// the 10%-pushed example, 0.5 let the wrinkles creep 3 cm in 100 held frames
// and fold at their crests.
#include <span>

#include "flagsim/core/vec3.hpp"
#include "flagsim/infill/fiber.hpp"

namespace flagsim::infill {

struct WrinkleParams {
  double k_r4 = 0.0;       ///< k r^4 of eqs. (1), (10): 1/2 E_f (pi/4) r^4, N m^2
  double k_prime = 1.0;    ///< k_prime of eq. (13) per unit length, N/m (see above)
  double tolerance = 0.0;  ///< relative |E - e| / max(E, e) below which a fiber is left alone
};

/// eq. (10): k = 1/2 E pi/4, times r^4.
double bending_constant_k_r4(double fiber_modulus_pa, double fiber_radius_m);

/// Turning angle at b between segments a->b and b->c, rad (0 for a straight fiber).
double turning_angle(const Vec3& a, const Vec3& b, const Vec3& c);

/// eq. (11): E = sum over interior nodes of F = k r^4 theta^2 (eqs. (1)-(2)).
double fiber_bending_energy(const Fiber& fiber, std::span<const Vec3> positions_m, double k_r4);

/// eq. (13): e = k_prime h (c - L)^2.
double fiber_target_energy(const Fiber& fiber, std::span<const Vec3> positions_m, double k_prime);

/// The wave count E = e picks (see above) for a fiber of chord `chord_m` and
/// slack `slack_m` (both m) over `segments` links: m = round((c/pi)
/// sqrt(k_prime dL / (2 k r^4))), at least 1, at most segments / 4.
int half_wave_count(double chord_m, double slack_m, int segments, const WrinkleParams& params);

/// The amplitude A (m) of y = A sin(m pi x / c), x in [0, c], whose length is
/// `length_m` (exactly, on a polyline of 4 `segments` pieces; 0 when it is no
/// longer than the chord): the small-slope estimate is too short at large slopes.
double wave_amplitude_m(double chord_m, double length_m, int half_waves, int segments);

/// Step 3.5 on one fiber, `normal` the cloth's normal there (any length, not
/// along the chord). Returns true if the fiber was re-laid.
bool rewrinkle_fiber(const Fiber& fiber, std::span<Vec3> positions_m, const Vec3& normal,
                     const WrinkleParams& params);

}  // namespace flagsim::infill
