#pragma once
/// \file
/// The checks of a session's actions before the run (session.hpp): the keys of
/// every $RUN stage (stage_spec) and of every $PRINT display, the $REPLACE
/// names, and the file names the displays will write. Everything that can be
/// wrong in them is reported before the first stage runs.

#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "pradis/integrators/bdf/options.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/linalg/ordering.hpp"
#include "pradis/lang/model_builder.hpp"

namespace pradis::lang {

/// A model_builder whose actions are checked (the base of session).
class action_checker : public model_builder {
 public:
  /// Builds the model and checks the actions. Throws lang_error.
  explicit action_checker(ast::program prog) : model_builder(std::move(prog)) { check_actions(); }

 protected:
  /// A label as part of a file name: characters other than letters, digits, '-' and '_' become '_'.
  static std::string file_part(const std::string& label) {
    std::string s;
    for (char ch : label) s += (std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_') ? ch : '_';
    return s;
  }

  // ---- actions: static checks ----------------------------------------------------------------
  void check_actions() {
    for (const auto& a : prog_.actions) {
      if (a.what == ast::action::kind::run) (void)stage_options(a.stage);
      if (a.what == ast::action::kind::print) (void)display_options(a.stage);
      if (a.what == ast::action::kind::replace)
        for (const auto& d : a.definitions) {
          if (!data_.count(d.name))
            fail(d.loc, "$REPLACE of an undefined $DATA name '" + d.name + "'" + did_you_mean(d.name, data_names()));
          (void)expand(d.values, "$REPLACE");
        }
    }
    // Two displays must not write the same file: labels that differ only in
    // characters replaced by '_' ("a b", "a_b"), or in case (a file system may
    // not tell "A" from "a"), or a label such as DISP2 that is also an unlabelled
    // display's name.
    std::map<std::string, location> files;
    int k = 0;
    for (const auto& a : prog_.actions) {
      if (a.what != ast::action::kind::print) continue;
      const ast::call& c = a.stage;
      const std::string f =
          upper(c.label.empty() ? upper(c.program) + std::to_string(++k) : (++k, file_part(c.label)));
      if (auto [it, fresh] = files.emplace(f, c.loc); !fresh)
        fail(c.loc, "this display would write the same files as the display at " + it->second.str() + " (<stem>." +
                        f + ".csv; labels become file names with characters other than letters, digits, - and _ "
                        "replaced by _, and case is ignored): give it another label");
    }
    bool any_run = false;
    for (const auto& a : prog_.actions) any_run = any_run || a.what == ast::action::kind::run;
    if (!any_run) fail(prog_.end, "missing section $RUN (at least one stage, e.g. `Calculation 'SHTERM (END=1)`)");
  }

  struct stage_spec {
    run_options opt;
    alpha_parameters scheme;  ///< the program's scheme, validated
    double save = 0;          ///< SAVE: checkpoint interval (0: none)
    location save_loc;        ///< where SAVE is
    location out_loc;         ///< where OUT is
    int optim = -1;           ///< OPTIM: ordering level 0..4, or -1 to choose by size
    bool bdf = false;         ///< the BDF program (bdf_opt), not a one-step scheme
    bdf_options bdf_opt;      ///< BDF: MAXORD, LQBAND, INDEX2, TURN, TURNMAX, RATES
  };

  /// The program that owns a scheme key (BETA, GAMMA, ALPHA, RHOINF), or "" for a common key.
  static std::string owner_of_key(const std::string& k) {
    if (k == "BETA" || k == "GAMMA") return "NEWMARK";
    if (k == "ALPHA") return "HHT";
    if (k == "RHOINF") return "GALPHA";
    if (k == "MAXORD" || k == "LQBAND" || k == "INDEX2" || k == "TURN" || k == "TURNMAX" || k == "RATES" ||
        k == "REFORM")
      return "BDF";
    return "";
  }

  stage_spec stage_options(const ast::call& c) const {
    const program_info* prog = find_program(integration_programs(), c.program);
    if (!prog) {
      std::string hint = find_element_passport(c.program)
                             ? " ('" + c.program + "' is an element model: use it under #STRUCTURE)"
                             : did_you_mean(c.program, names_of(integration_programs()));
      fail(c.program_loc, "unknown integration program '" + c.program + "'" + hint);
    }
    stage_spec s;
    newmark_parameters np{};
    double alpha = hht{}.alpha(), rho = generalized_alpha{}.rho_inf();
    std::set<std::string> seen;
    bool has_end = false;
    static const std::vector<std::string> known{"END",   "OUT",   "SMAX",  "SMIN",    "IGNORE",  "DABSU",
                                                "DRLTU", "DABSI", "DRLTI", "ITR",     "SECOND",  "BETA",
                                                "GAMMA", "ALPHA", "RHOINF", "DABSX",  "DRLTX",   "CONTROL",
                                                "PREDICT", "SAVE",  "OPTIM",   "MAXORD", "LQBAND",  "INDEX2",
                                                "TURN",  "TURNMAX", "RATES", "REFORM", "NSTEPMAX"};
    for (const auto& g : c.args)
      for (const auto& it : g) {
        if (it.what != ast::item::kind::keyed)
          fail(it.loc, "an integration program takes KEY=value arguments (e.g. END=1)");
        const std::string& k = it.text;
        if (!seen.insert(k).second) fail(it.loc, "key " + k + " is given twice");
        const ast::item& v = it.value.front();
        bool is_unimpl = false;
        for (const auto& u : unimplemented_run_keys()) is_unimpl = is_unimpl || u == k;
        if (is_unimpl) {
          std::string own;
          for (const char* q : {"BETA", "GAMMA", "ALPHA", "RHOINF"})
            if (owner_of_key(q) == c.program) own += std::string(" ") + q;
          fail(it.loc, "key " + k + " of " + c.program +
                           " is not implemented by pradis yet (implemented: END OUT SMAX SMIN IGNORE DABSU DRLTU DABSI "
                           "DRLTI ITR SECOND DABSX DRLTX CONTROL PREDICT SAVE OPTIM NSTEPMAX" +
                           own + ")");
        }
        if (c.program == "BDF")
          for (const char* no : {"DABSU", "DRLTU", "DABSI", "DRLTI", "SECOND", "PREDICT"})
            if (k == no)
              fail(it.loc, "key " + k + " does not apply to BDF (its Newton and error tests are weighted by DRLTX and "
                           "DABSX; keys of BDF: END OUT SMAX SMIN IGNORE DRLTX DABSX CONTROL ITR SAVE OPTIM NSTEPMAX "
                           "MAXORD LQBAND INDEX2 TURN TURNMAX RATES)");
        const std::string owner = owner_of_key(k);
        if (!owner.empty() && owner != c.program)
          fail(it.loc, "key " + k + " belongs to " + owner + ", not to " + c.program +
                           (c.program == "SHTERM" ? " (SHTERM has fixed BETA = 1/2, GAMMA = 1)" : ""));
        if (k == "END") {
          s.opt.end = scalar(v, "END");
          has_end = true;
        } else if (k == "OUT") {
          s.opt.out = scalar(v, "OUT");
          s.out_loc = it.loc;
        }
        else if (k == "SMAX")
          s.opt.smax = scalar(v, "SMAX");
        else if (k == "SMIN")
          s.opt.smin = scalar(v, "SMIN");
        else if (k == "IGNORE")
          s.opt.ignore = whole(v, "IGNORE", 0, 1) == 1;
        else if (k == "SECOND")
          s.opt.newton.second = whole(v, "SECOND", 0, 1) == 1;
        else if (k == "DABSU")
          s.opt.newton.dabsu = scalar(v, "DABSU");
        else if (k == "DRLTU")
          s.opt.newton.drltu = scalar(v, "DRLTU");
        else if (k == "DABSI")
          s.opt.newton.dabsi = scalar(v, "DABSI");
        else if (k == "DRLTI")
          s.opt.newton.drlti = scalar(v, "DRLTI");
        else if (k == "ITR")
          s.opt.newton.itr = whole(v, "ITR", 1, 1000);
        else if (k == "NSTEPMAX")
          s.opt.max_steps = whole(v, "NSTEPMAX", 0, 2000000000);
        else if (k == "DABSX") {
          s.opt.dabsx = scalar(v, "DABSX");
          s.opt.error_control = true;
        } else if (k == "DRLTX") {
          s.opt.drltx = scalar(v, "DRLTX");
          s.opt.error_control = true;
        } else if (k == "CONTROL") {
          s.opt.control = scalar(v, "CONTROL");
          s.opt.error_control = true;
        } else if (k == "PREDICT") {
          s.opt.predict = whole(v, "PREDICT", 0, 1) == 1;
          s.opt.error_control = true;
        } else if (k == "SAVE") {
          s.save = scalar(v, "SAVE");
          s.save_loc = it.loc;
          if (!(s.save > 0) || !std::isfinite(s.save))
            fail(it.loc, "SAVE = " + num(s.save) +
                             " must be a number > 0 (the interval of simulated time between checkpoints)");
        } else if (k == "MAXORD") {
          s.bdf_opt.max_order = whole(v, "MAXORD", 1, 5);
        } else if (k == "LQBAND") {
          s.bdf_opt.lq_renormalise = scalar(v, "LQBAND");
          if (!(s.bdf_opt.lq_renormalise >= 0) || !std::isfinite(s.bdf_opt.lq_renormalise))
            fail(it.loc, "LQBAND = " + num(s.bdf_opt.lq_renormalise) +
                             " must be a number >= 0 (the band of the quaternion norm Lq around 1 beyond which a "
                             "rotational node is scaled back to Lq = 1; 0: after every step, >= 0.1: never)");
        } else if (k == "INDEX2") {
          s.bdf_opt.stabilised_index2 = whole(v, "INDEX2", 0, 1) == 1;
        } else if (k == "TURN") {
          const int turn = whole(v, "TURN", 0, 2);
          s.bdf_opt.rotated_jacobian = turn > 0;
          s.bdf_opt.body_frame = turn == 2;
        } else if (k == "TURNMAX") {
          s.bdf_opt.turn_refresh = scalar(v, "TURNMAX");
          if (!(s.bdf_opt.turn_refresh >= 0))
            fail(it.loc, "TURNMAX = " + num(s.bdf_opt.turn_refresh) +
                             " must be a number >= 0 (the turn [rad] of a rotational node in the global frame after "
                             "which the kept Newton matrix is refreshed; >= pi: never)");
        } else if (k == "RATES") {
          s.bdf_opt.rotation_rates = whole(v, "RATES", 0, 1) == 1;
        } else if (k == "REFORM") {
          s.bdf_opt.reform_jacobian = whole(v, "REFORM", 0, 1) == 1;
        } else if (k == "OPTIM")
          s.optim = whole(v, "OPTIM", linalg::optim_min_level, linalg::optim_max_level);
        else if (k == "BETA")
          np.beta = scalar(v, "BETA");
        else if (k == "GAMMA")
          np.gamma = scalar(v, "GAMMA");
        else if (k == "ALPHA") {
          alpha = scalar(v, "ALPHA");
          try {
            (void)hht(alpha);
          } catch (const pradis::error&) {
            fail(it.loc, "HHT: ALPHA = " + num(alpha) + " is outside its valid range -1/3 <= ALPHA <= 0");
          }
        } else if (k == "RHOINF") {
          rho = scalar(v, "RHOINF");
          try {
            (void)generalized_alpha(rho);
          } catch (const pradis::error&) {
            fail(it.loc, "GALPHA: RHOINF = " + num(rho) + " is outside its valid range 0 <= RHOINF <= 1");
          }
        } else
          fail(it.loc, "unknown key " + k + " of " + c.program + did_you_mean(k, known));
      }
    if (!has_end) fail(c.args_loc, c.program + " needs END=<end time>");
    if (c.program == "BDF") {
      s.bdf = true;
      s.opt.error_control = true;  // BDF always controls its local error (DRLTX, DABSX)
      return s;
    }
    try {
      if (c.program == "SHTERM")
        s.scheme = stoermer{}.coefficients_set();
      else if (c.program == "NEWMARK")
        s.scheme = newmark(np).coefficients_set();
      else if (c.program == "HHT")
        s.scheme = hht(alpha).coefficients_set();
      else
        s.scheme = generalized_alpha(rho).coefficients_set();
    } catch (const pradis::error& e) {
      fail(c.args_loc, e.message());
    }
    return s;
  }

  struct display_spec {
    std::vector<int> columns;
    double start = -HUGE_VAL, end = HUGE_VAL;
    std::optional<double> threshold;  ///< PEAK: THRESHOLD
    bool magnitude = false;           ///< PEAK: MAGNITUDE=1
  };

  display_spec display_options(const ast::call& c) const {
    if (!find_program(display_programs(), c.program))
      fail(c.program_loc,
           "unknown display program '" + c.program + "'" + did_you_mean(c.program, names_of(display_programs())));
    display_spec d;
    for (const auto& g : c.args)
      for (const auto& it : g) {
        if (it.what == ast::item::kind::keyed) {
          if (it.text == "START")
            d.start = scalar(it.value.front(), "START");
          else if (it.text == "END")
            d.end = scalar(it.value.front(), "END");
          else if (it.text == "THRESHOLD" && c.program == "PEAK")
            d.threshold = scalar(it.value.front(), "THRESHOLD");
          else if (it.text == "MAGNITUDE" && c.program == "PEAK")
            d.magnitude = whole(it.value.front(), "MAGNITUDE", 0, 1) == 1;
          else if (it.text == "OUT" || it.text == "FORMF")
            fail(it.loc,
                 "key " + it.text + " of " + c.program + " is not implemented by pradis yet (implemented: START END)");
          else
            fail(it.loc, "unknown key " + it.text + " of " + c.program +
                             did_you_mean(it.text, c.program == "PEAK"
                                                       ? std::vector<std::string>{"START", "END", "THRESHOLD", "MAGNITUDE"}
                                                       : std::vector<std::string>{"START", "END"}));
        } else if (it.what == ast::item::kind::name && c.program == "VTK") {
          fail(it.loc, "VTK draws the model's spatial elements and takes no output labels (only START=, END=)");
        } else if (it.what == ast::item::kind::name) {
          int found = -1;
          std::vector<std::string> labels;
          for (std::size_t k = 0; k < outputs_.size(); ++k) {
            labels.push_back(outputs_[k].label);
            if (outputs_[k].label == it.text) found = static_cast<int>(k);
          }
          if (found < 0) fail(it.loc, "no output labelled '" + it.text + "'" + did_you_mean(it.text, labels));
          d.columns.push_back(found);
        } else {
          fail(it.loc, "a display program takes output labels and START=, END=");
        }
      }
    if (c.program == "VTK") return d;
    if (d.columns.empty())
      for (std::size_t k = 0; k < outputs_.size(); ++k) d.columns.push_back(static_cast<int>(k));
    if (d.columns.empty()) fail(c.loc, "nothing to display: the model has no #OUTPUT");
    return d;
  }

};

}  // namespace pradis::lang
