// libFuzzer harness: `vibrissa solve` end to end — case JSON text -> reader -> solve -> result JSON.
#include <cmath>
#include <cstdint>
#include <string_view>

#include "fuzz_contract.hpp"
#include "vibrissa/io/case_json.hpp"
#include "vibrissa/io/json_input.hpp"

namespace {

void check_contract(const vibrissa::Case& c, const vibrissa::Solution& s) {
  using vibrissa::Status;
  const auto& wf = s.whisker_frame;
  const bool finite = std::isfinite(s.force_magnitude) && std::isfinite(s.arc_length) && std::isfinite(s.angle) &&
                      s.contact_point_W.allFinite() && s.force_W.allFinite() && s.moment_W.allFinite() &&
                      wf.force.allFinite() && wf.moment.allFinite() && std::isfinite(wf.FT) && std::isfinite(wf.MB) &&
                      std::isfinite(wf.FD) && std::isfinite(wf.MD) && std::isfinite(s.residual) &&
                      (!s.normal_force || std::isfinite(*s.normal_force)) &&
                      (!s.edge_force || std::isfinite(*s.edge_force)) &&
                      (!s.other_root_arc_length || std::isfinite(*s.other_root_arc_length));
  if (!finite) vibrissa::fuzz::finding("non-finite field in a Solution");
  for (const auto& p : s.shape_W)
    if (!p.allFinite()) vibrissa::fuzz::finding("non-finite node in Solution::shape");
  // Contact modes report the residual in metres against options.tolerance (dead loads in newtons, the
  // base-wrench inverse as sqrt(chi2), judged against the noise instead).
  const bool metres =
      !std::holds_alternative<vibrissa::DeadLoad>(c.load) && !std::holds_alternative<vibrissa::BaseWrenchLoad>(c.load);
  if (s.status == Status::converged && metres && !(s.residual <= c.options.tolerance))
    vibrissa::fuzz::finding("converged with a residual above the tolerance");
  // Every reported residual belongs to the returned state (issue 23): a dead load's residual [N] is the
  // misfit of the returned force, in the max-norm of the whisker frame (between |d|/sqrt(3) and |d|).
  if (const auto* dead = std::get_if<vibrissa::DeadLoad>(&c.load); dead && s.force_magnitude > 0.0) {
    const double misfit = (s.force_W - dead->force).norm();
    const double slack = 1e-9 * dead->force.norm() + 1e-300;
    if (!(s.residual <= misfit + slack && s.residual >= misfit / std::sqrt(3.0) - slack))
      vibrissa::fuzz::finding("dead load: the residual is not the misfit of the returned force");
  }
  (void)vibrissa::case_result_to_json(c, s).dump();  // the writer: every number finite, so no null
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  vibrissa::fuzz::expect_no_crash([&] {
    const vibrissa::Case c = vibrissa::case_from_json(vibrissa::io::parse_json_text(text, "fuzz"));
    if (c.whisker.links() > 2000) return;  // legal but slow: keeps executions per second useful
    check_contract(c, vibrissa::solve_case(c));
  });
  return 0;
}
