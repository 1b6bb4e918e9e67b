#pragma once
// Error bound on an edge-mode contact position for a friction coefficient mu (spec §3.4, eq. (7)):
//   z_error = sgn(z_edge − z_onset) · 4L / (3 E π R_base^4) · mu F_N s^3 / (L − s),
// with L = R_base / (R_base − R_tip) · S the length of the cone the tapered whisker belongs to (eq. (5)).
// A linear tapered-cantilever estimate: reliable for small deflections (spec §3.3), meaningless as s -> L.

namespace vibrissa::array {

/// L of eq. (5) [m] from the arc length S [m] and the taper ratio R_base / R_tip.
double cone_length(double arc_length, double taper_ratio);

/// z_error of eq. (7) [m] (signed along the edge). `direction` is z_edge − z_onset (only its sign is used;
/// zero gives zero). s_applied [m], normal_force F_N [N], youngs_modulus E [Pa], base_radius [m].
double contact_error_bound(double direction, double mu, double normal_force, double s_applied, double arc_length,
                           double base_radius, double taper_ratio, double youngs_modulus);

}  // namespace vibrissa::array
