#pragma once
// Full-array edge-mode simulation (spec §3.4, §4.4, Fig. 4a): every whisker of a morphology whisks with the
// given kinematics, for each of a list of head pitches, against a scene of edges. Per whisker and frame:
//   one ContactTracker per (pitch, whisker) run decides onset, solve, push-past and release
// (contact/tracker.hpp, docs/conventions.md "Contact tracking"). The first frame is always free.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vibrissa/array/head.hpp"
#include "vibrissa/contact/tracker.hpp"
#include "vibrissa/core/run_control.hpp"
#include "vibrissa/dynamics/contact.hpp"
#include "vibrissa/dynamics/linear_model.hpp"
#include "vibrissa/array/kinematics.hpp"
#include "vibrissa/array/morphology.hpp"
#include "vibrissa/array/objects.hpp"

namespace vibrissa::array {

// Contact states and modes are the library's (vibrissa::ContactState in solve/solution.hpp,
// vibrissa::ContactMode in contact/tracker.hpp); the array runs the edge modes only.

struct SimulationConfig {
  Morphology morphology;
  WhiskingKinematics whisking;
  HeadMotion head;
  std::vector<double> pitches{0.0};  ///< extra head pitch of each run [rad] (a sweep when more than one)
  std::vector<SceneObject> objects;
  std::vector<double> times;  ///< frame times [s], strictly increasing
  ContactMode mode = ContactMode::edge;
  double mu = 0.48;     ///< friction coefficient: eq. (7) bound, and the frictional mode (data sheet §4)
  int links = 100;      ///< links per whisker (spec §2.1)
  double tolerance = 1e-10;  ///< solver contact residual [m]
  int max_iterations = 100;
  bool thickness = true;  ///< surfaces: the whisker's surface touches them (docs/objects.md)
  std::vector<int> render_frames;  ///< frames whose rest and deflected shapes are kept (for the animation)
  int render_pitch = 0;            ///< index into `pitches` of the rendered run
  int threads = 0;                 ///< OpenMP threads (0: all)
  /// `vibrissa array --dynamics` (docs/array.md, docs/dynamics.md): every whisker driven by the whisking and head
  /// motion through the dynamics integrator (dynamics/simulate.hpp), touching the scene's infinite edges and pegs
  /// fixed in the world as contacts during motion (friction mu in the frictional edge mode). Frames must then be
  /// equally spaced.
  std::optional<dynamics::DynamicsProperties> dynamics;
};

/// Throws std::invalid_argument naming the field for anything unusable.
void validate(const SimulationConfig& config);

/// Results laid out [pitch][whisker][frame] (vectors: [...][3]). Frames without contact hold zeros.
struct ArrayResult {
  std::size_t n_pitches = 0, n_whiskers = 0, n_frames = 0, n_nodes = 0;
  std::vector<double> times;    ///< [s]
  std::vector<double> pitches;  ///< [rad]
  std::vector<std::string> labels;  ///< whisker labels, e.g. "C2R"

  std::vector<std::int8_t> state;          ///< ContactState
  std::vector<std::int8_t> solver_status;  ///< vibrissa::Status of the frame's solve; -1: no solve
  std::vector<std::int16_t> edge;          ///< index of the touched edge (edges_in_world order); -1: none
  std::vector<double> s_applied;           ///< arc length of contact [m]
  std::vector<double> contact_W;           ///< contact point, world [m] (x3)
  std::vector<double> force_W, moment_W;   ///< at the base, world [N], [N·m] (x3)
  std::vector<double> force_B, moment_B;   ///< at the base, whisker frame (Fx, Fy, Fz), (Mx, My, Mz) (x3)
  std::vector<double> FT, MB, FD, MD;      ///< spec §2.4 [N], [N·m], [rad], [rad]
  std::vector<double> normal_force;        ///< F_N, force normal to the edge [N] (surfaces: F . n)
  std::vector<double> edge_force;          ///< force along the edge [N] (non-zero only with friction; surfaces: F . b)
  std::vector<double> z_edge;              ///< contact position along the edge from its p0 [m]
  std::vector<double> z_error;             ///< eq. (7) bound for `mu` [m]

  /// Source angles of each whisker, [whisker][frame] [rad] (independent of the head).
  std::vector<double> theta, phi, zeta;
  /// Base point of each whisker in the world, [pitch][whisker][frame][3] [m].
  std::vector<double> base_W;

  /// Rendered frames of run `render_pitch`: [render][whisker][node][3] rest and deflected shapes [m].
  std::vector<int> render_frames;
  std::vector<float> rest_shapes, deflected_shapes;
  /// Edges at each rendered frame, [render][edge][2 ends][3] [m] (infinite edges clipped to ±60 mm).
  std::vector<float> render_edges;
  std::size_t n_edges = 0;
  /// Surfaces (scenes of objects): each object's pose at each rendered frame, [render][object][12] (R_WO row by
  /// row, then p_WO [m]); the objects themselves are the config's (io::shape_to_json).
  std::vector<float> render_object_poses;
  std::size_t n_objects = 0;

  /// With dynamics: tip displacement from rest in the whisker frame [m] (x3), and integrator steps per run.
  std::vector<double> tip_displacement_B;
  std::size_t dynamics_steps = 0, dynamics_rejected_steps = 0;
  /// With dynamics: the contact events (touch, slip, stick, release; `object` indexes the edges) of each run,
  /// [pitch * n_whiskers + whisker], in time order (times from the first frame).
  std::vector<std::vector<dynamics::ContactEvent>> contact_events;

  std::size_t solves = 0;          ///< edge solves performed
  std::size_t failed_solves = 0;   ///< solves that ended not_converged (counted as pushed past)
  double wall_seconds = 0.0;

  [[nodiscard]] std::size_t index(std::size_t pitch, std::size_t whisker, std::size_t frame) const {
    return (pitch * n_whiskers + whisker) * n_frames + frame;
  }
  [[nodiscard]] ContactState state_at(std::size_t p, std::size_t w, std::size_t f) const {
    return static_cast<ContactState>(state[index(p, w, f)]);
  }
  [[nodiscard]] Eigen::Vector3d vec(const std::vector<double>& v, std::size_t p, std::size_t w, std::size_t f) const {
    const std::size_t i = 3 * index(p, w, f);
    return {v[i], v[i + 1], v[i + 2]};
  }
};

/// Frame times t_k = start + k (end − start) / (frames − 1).
std::vector<double> uniform_times(double start, double end, int frames);

/// Runs every (pitch, whisker) pair in parallel. Progress counts whisker-frames (pitches x whiskers x frames),
/// advanced per (pitch, whisker) run; cancel is polled per run.
ArrayResult simulate_array(const SimulationConfig& config, const RunControl& control = {});

}  // namespace vibrissa::array
