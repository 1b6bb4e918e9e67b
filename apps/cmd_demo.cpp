// `vibrissa demo`: the built-in default case. A whisker with the paper's dimensions (§2.1: E 3.3 GPa,
// nu 0.38, base radius 100 um, taper 15) protracted against a vertical peg, solved in edge mode
// (frictionless) and in contact-point mode through a point 1 mm higher on the peg (friction implicit).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "commands.hpp"
#include "vibrissa/io/case_json.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa::cli {
namespace {

void print(const char* title, const Solution& s, double micros) {
  const auto& wf = s.whisker_frame;
  constexpr double deg = 180.0 / std::numbers::pi;
  std::printf("\n%s\n", title);
  std::printf("  status            %s (%s)\n", std::string(to_string(s.status)).c_str(), std::string(s.message).c_str());
  std::printf("  solve time        %.1f us, %d iterations, residual %.2e m\n", micros, s.iterations, s.residual);
  std::printf("  arc length s      %.3f mm\n", s.arc_length * 1e3);
  std::printf("  contact point     (%.3f, %.3f, %.3f) mm, world\n", s.contact_point_W.x() * 1e3,
              s.contact_point_W.y() * 1e3, s.contact_point_W.z() * 1e3);
  std::printf("  force F           (%.4f, %.4f, %.4f) mN, world\n", s.force_W.x() * 1e3, s.force_W.y() * 1e3,
              s.force_W.z() * 1e3);
  std::printf("  moment M          (%.3f, %.3f, %.3f) uN·m, world, about the base\n", s.moment_W.x() * 1e6,
              s.moment_W.y() * 1e6, s.moment_W.z() * 1e6);
  std::printf("  whisker frame     Fx %.4f mN   Mx %.4f uN·m\n", wf.force.x() * 1e3, wf.moment.x() * 1e6);
  std::printf("                    F_T %.4f mN  M_B %.3f uN·m  F_D %.1f deg  M_D %.1f deg\n", wf.FT * 1e3,
              wf.MB * 1e6, wf.FD * deg, wf.MD * deg);
  if (s.normal_force)
    std::printf("  normal force      %.4f mN; along the peg %.4f mN (mu = %.3f)\n", *s.normal_force * 1e3,
                *s.edge_force * 1e3, *s.normal_force > 0 ? *s.edge_force / *s.normal_force : 0.0);
}

template <class F>
Solution timed(F&& f, double& micros) {
  const auto t0 = std::chrono::steady_clock::now();
  Solution s = f();
  micros = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

}  // namespace

void register_demo(CLI::App& app) {
  auto* cmd = app.add_subcommand("demo", "Run the built-in case: a whisker protracted against a peg");
  auto out = std::make_shared<std::string>();
  cmd->add_option("-o,--output", *out, "also write both results as JSON")->check(output_path());
  cmd->callback([out] {
    WhiskerProperties props;  // spec §2.1 defaults
    const double length = 0.040, curvature = 12.0;  // 40 mm whisker, y = 12 x^2 [1/m] (~ 0.012 /mm)
    Pose pose;
    pose.theta = 10.0 * std::numbers::pi / 180.0;  // protracted 10 deg past the peg at x = 20 mm
    pose.phi = 10.0 * std::numbers::pi / 180.0;    // elevated 10 deg and rolled 30 deg: the contact slips
    pose.zeta = 30.0 * std::numbers::pi / 180.0;   // along the peg in edge mode
    const Whisker whisker = Whisker::from_parabola(length, curvature, props, pose);
    Edge peg;
    peg.point = {0.020, 0.0, 0.0};
    peg.direction = {0.0, 0.0, 1.0};
    std::printf("vibrissa demo: %g mm whisker (y = %g x^2 /m, base radius %g um, taper %g, E %g GPa, nu %g,"
                " N = %d links)\n  protracted to theta = 10 deg (phi = 10 deg, zeta = 30 deg) against a vertical peg at (20, 0) mm\n",
                length * 1e3, curvature, props.base_radius * 1e6, props.taper_ratio, props.youngs_modulus / 1e9,
                props.poisson_ratio, props.links);
    SolveOptions opt;
    double t_edge = 0.0, t_point = 0.0;
    const Solution edge = timed([&] { return solve_edge(whisker, peg, std::nullopt, opt); }, t_edge);
    print("Edge mode (frictionless slip along the peg):", edge, t_edge);
    const Eigen::Vector3d tracked = edge.contact_point_W + Eigen::Vector3d(0, 0, 1e-3);
    const Solution point = timed(
        [&] { return solve_point(whisker, tracked, std::nullopt, opt, nullptr, peg.direction); }, t_point);
    print("Contact-point mode (tracked contact 1 mm above the frictionless one; friction implicit):", point, t_point);
    if (!out->empty())
      write_json_file(*out, {{"edge", solution_to_json(edge)}, {"point", solution_to_json(point)}});
  });
}

}  // namespace vibrissa::cli
