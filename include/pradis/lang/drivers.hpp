#pragma once
/// \file
/// The integration drivers of a model-language session: the one-step driver
/// (SHTERM, NEWMARK, HHT, GALPHA: pradis::simulation with a stage_scheme) and
/// the variable-order BDF driver (BDF: pradis::bdf_simulation). One of them is
/// current; a stage with another scheme or kind continues from its state in a
/// new driver (continue_from(): the checkpoint's fields, not serialised), and
/// $SAVE / $RESTORE write and read the current one's checkpoint with the
/// session's scheme record.

#include <cstring>
#include <istream>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>

#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/simulation.hpp"
#include "pradis/lang/run_types.hpp"
#include "pradis/linalg/sparse_lu.hpp"

namespace pradis::lang {

/// The two drivers of a session (a CRTP base: `Session::attach(sim)` adds the
/// session's output and step observers to a driver it makes).
template <class Session>
class stage_drivers {
 public:
  /// The one-step driver: OPTIM picks the ordering level of its solver per stage.
  using sim_type = simulation<library_model, stage_scheme, linalg::sparse_lu<linalg::optim_ordering>>;
  /// The BDF driver, with the same solver policy.
  using bdf_type = bdf_simulation<library_model, linalg::sparse_lu<linalg::optim_ordering>>;

  /// The one-step driver (null before the first one-step stage or $RESTORE; its
  /// state is not the current one while a BDF stage is current: see bdf_active()).
  const sim_type* simulation_ptr() const noexcept { return sim_.get(); }
  /// The BDF driver (null before the first BDF stage).
  const bdf_type* bdf_ptr() const noexcept { return bdf_.get(); }
  /// Whether the current driver is the BDF one.
  bool bdf_active() const noexcept { return bdf_active_; }

 protected:
  explicit stage_drivers(library_model& m) : driven_(m) {}

  /// Calls f with the current driver (one of them must exist).
  template <class F>
  decltype(auto) visit(F&& f) {
    return bdf_active_ ? f(*bdf_) : f(*sim_);
  }
  template <class F>
  decltype(auto) visit(F&& f) const {
    return bdf_active_ ? f(*bdf_) : f(*sim_);
  }
  /// Whether a driver exists.
  bool has_driver() const noexcept { return bdf_active_ ? bdf_ != nullptr : sim_ != nullptr; }

  /// Makes the one-step driver with scheme p current, continuing from the current
  /// driver's state (continue_from()) if a stage has run. A change of
  /// scheme, or a change from BDF, starts the scheme afresh (p = a), unless the
  /// previous scheme is not known (a $RESTORE of a checkpoint without the record).
  void use_scheme(const alpha_parameters& p) {
    if (!bdf_active_ && sim_ && same_scheme(scheme_, p)) {
      scheme_known_ = true;
      return;
    }
    auto next = make_sim(p);
    if (has_driver() && started_) {
      visit([&](const auto& s) { next->continue_from(s); });
      if (scheme_known_ || bdf_active_) next->restart_scheme();
    }
    sim_ = std::move(next);
    bdf_active_ = false;
    scheme_ = p;
    scheme_known_ = true;
  }

  /// Makes a BDF driver with options o current, continuing from the current
  /// driver's state if a stage has run (BDF starts every stage at order 1).
  void use_bdf(const bdf_options& o) {
    if (bdf_active_ && bdf_ && bdf_->options() == o) return;
    auto next = std::make_unique<bdf_type>(driven_, o);
    static_cast<Session*>(this)->attach(*next);
    if (has_driver() && started_) visit([&](const auto& s) { next->continue_from(s); });
    bdf_ = std::move(next);
    bdf_active_ = true;
  }

  /// Runs one piece of a stage cut at the checkpoint times (SAVE) with the options o. The
  /// stage's NSTEPMAX budget, max_steps, counts its steps since the statistics showed `steps0`;
  /// `end` is the stage's END.
  void run_piece(run_options o, double end, long max_steps, long steps0) {
    const double now = visit([](const auto& s) { return s.time(); });
    if (max_steps > 0) {
      const long used = visit([](const auto& s) { return s.statistics().steps; }) - steps0;
      if (used >= max_steps) throw pradis::detail::step_budget_error(max_steps, now, end, {});
      o.max_steps = max_steps - used;
    }
    try {
      visit([&](auto& s) { (void)s.run(o); });
    } catch (const pradis::error& e) {
      if (e.code() != error_code::step_budget || max_steps <= 0) throw;
      // The message names the stage's budget, not the piece's.
      throw pradis::detail::step_budget_error(max_steps, visit([](const auto& s) { return s.time(); }), end, {});
    }
  }

  /// The record a session appends to a checkpoint: the last one-step scheme's
  /// four parameters and this tag at the very end (a checkpoint of the library has none).
  static constexpr char scheme_tag[8] = {'P', 'R', 'L', 'A', 'N', 'G', '0', '1'};
  static constexpr std::size_t scheme_record = 4 * sizeof(double) + sizeof scheme_tag;

  /// Writes the current driver's checkpoint followed by the scheme record
  /// (throws pradis::error from the driver).
  void write_checkpoint_to(std::ostream& f) const {
    visit([&](const auto& s) { s.save_checkpoint(f); });
    const double q[4] = {scheme_.alpha_m, scheme_.alpha_f, scheme_.beta, scheme_.gamma};
    f.write(reinterpret_cast<const char*>(q), sizeof q);
    f.write(scheme_tag, sizeof scheme_tag);
  }

  /// Restores the bytes of a checkpoint into a new one-step driver (the scheme of
  /// its record, or SHTERM's). Returns an error message instead of changing
  /// anything when the record is damaged or the checkpoint is refused.
  std::optional<std::string> restore_from(const std::string& bytes) {
    alpha_parameters q = stoermer{}.coefficients_set();
    bool known = false;
    if (bytes.size() >= scheme_record &&
        std::memcmp(bytes.data() + bytes.size() - sizeof scheme_tag, scheme_tag, sizeof scheme_tag) == 0) {
      double v[4];
      std::memcpy(v, bytes.data() + bytes.size() - scheme_record, sizeof v);
      // Ranges of the four programs: alpha_m, alpha_f < 1, 0 < beta <= 1, 1/2 <= gamma <= 3/2.
      const bool ok = std::isfinite(v[0]) && std::isfinite(v[1]) && v[0] < 1 && v[1] < 1 && v[2] > 0 &&
                      v[2] <= 1 && v[3] >= 0.5 && v[3] <= 1.5;
      if (!ok) return "its record of the integration scheme is damaged";
      q = {v[0], v[1], v[2], v[3]};
      known = true;
    }
    auto next = make_sim(q);
    std::istringstream is(bytes);
    try {
      next->load_checkpoint(is);
    } catch (const pradis::error& e) {
      return e.message();
    }
    sim_ = std::move(next);
    bdf_active_ = false;
    scheme_ = q;
    scheme_known_ = known;
    started_ = true;
    return std::nullopt;
  }

  bool started_ = false;  ///< a stage has run (or a checkpoint was restored)

 private:
  static bool same_scheme(const alpha_parameters& a, const alpha_parameters& b) {
    return a.alpha_m == b.alpha_m && a.alpha_f == b.alpha_f && a.beta == b.beta && a.gamma == b.gamma;
  }
  std::unique_ptr<sim_type> make_sim(const alpha_parameters& p) {
    auto s = std::make_unique<sim_type>(driven_, stage_scheme(p));
    static_cast<Session*>(this)->attach(*s);
    return s;
  }

  library_model& driven_;
  std::unique_ptr<sim_type> sim_;
  std::unique_ptr<bdf_type> bdf_;
  bool bdf_active_ = false;
  alpha_parameters scheme_{};
  bool scheme_known_ = false;  ///< false after restoring a checkpoint without the scheme record
};

}  // namespace pradis::lang
