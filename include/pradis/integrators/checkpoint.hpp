#pragma once
/// \file
/// The checkpoint format of pradis::simulation (version 5) and the model
/// fingerprint it carries.
///
/// Layout: the 8-byte magic "PRADCKPT", the format version (uint32), the
/// payload length in bytes (uint64), the payload and its FNV-1a 64-bit
/// checksum (uint64). The payload is written field by field (int64 and double
/// values, and vectors as a uint64 length followed by their doubles), in the
/// machine's byte order. Bytes after the checksum are not read (a language
/// session appends its own record there). A wrong magic, another version, a
/// truncated file or a checksum mismatch is refused with io_error before any
/// field is used; the simulation checks the values themselves (finite, counts
/// not negative, sizes of the model).

#include <algorithm>
#include <concepts>
#include <cstdint>
#include <cstring>
#include <istream>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/error.hpp"
#include "pradis/integrators/options.hpp"

namespace pradis {

/// The checkpoint format version written and read by this pradis.
/// Version 3 added the DOF classes of the zero step (checkpoint_data::dof_classes); a version-2 checkpoint is refused
/// (a restored run needs them to leave index-3 multipliers out of its error tests). Version 4 has the same fields;
/// its model fingerprint also covers the model's nodes (node kinds), so a version-3 checkpoint is refused as well.
/// Version 5 has the same fields and a fourth DOF class, the massless DOFs whose velocity is an unknown of its own
/// (a source current; class 1 before), whose velocity the BDF driver keeps in its norms; a version-4 checkpoint is
/// refused.
inline constexpr std::uint32_t checkpoint_version = 5;

namespace detail {

inline constexpr char checkpoint_magic[8] = {'P', 'R', 'A', 'D', 'C', 'K', 'P', 'T'};
/// The magic of the unversioned format of earlier pradis (refused with a plain message).
inline constexpr char checkpoint_magic_v1[8] = {'P', 'R', 'A', 'D', 'C', 'K', '0', '1'};

/// FNV-1a, 64 bit.
inline std::uint64_t fnv1a(const void* p, std::size_t n, std::uint64_t h = 1469598103934665603ull) {
  const auto* b = static_cast<const unsigned char*>(p);
  for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  return h;
}

/// Collects the payload of a checkpoint field by field, then writes it framed.
class checkpoint_writer {
 public:
  void put_int(std::int64_t x) { raw(&x, sizeof x); }
  void put_double(double x) { raw(&x, sizeof x); }
  void put_vector(std::span<const double> v) {
    put_int(static_cast<std::int64_t>(v.size()));
    raw(v.data(), v.size() * sizeof(double));
  }
  /// Writes magic, version, length, payload and checksum.
  void write(std::ostream& os) const {
    const std::uint32_t version = checkpoint_version;
    const std::uint64_t n = buf_.size(), sum = fnv1a(buf_.data(), buf_.size());
    os.write(checkpoint_magic, sizeof checkpoint_magic);
    os.write(reinterpret_cast<const char*>(&version), sizeof version);
    os.write(reinterpret_cast<const char*>(&n), sizeof n);
    os.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    os.write(reinterpret_cast<const char*>(&sum), sizeof sum);
    if (!os) throw error(error_code::io_error, "cannot write the checkpoint");
  }

 private:
  void raw(const void* p, std::size_t n) {
    if (n > 0) buf_.append(static_cast<const char*>(p), n);  // an empty vector's data() may be null
  }
  std::string buf_;
};

/// Reads and verifies the frame of a checkpoint, then hands out its fields.
class checkpoint_reader {
 public:
  /// Reads the frame; throws io_error ("not a pradis checkpoint", "checkpoint
  /// version ...", "checkpoint damaged: ...") unless it is intact.
  explicit checkpoint_reader(std::istream& is) {
    char magic[sizeof checkpoint_magic];
    is.read(magic, sizeof magic);
    if (is && std::memcmp(magic, checkpoint_magic_v1, sizeof magic) == 0)
      throw error(error_code::io_error, "checkpoint version 1 (an unversioned checkpoint of an earlier pradis) "
                                        "cannot be read; this pradis reads version " +
                                            std::to_string(checkpoint_version));
    if (!is || std::memcmp(magic, checkpoint_magic, sizeof magic) != 0)
      throw error(error_code::io_error, "not a pradis checkpoint");
    std::uint32_t version = 0;
    std::uint64_t n = 0, sum = 0;
    is.read(reinterpret_cast<char*>(&version), sizeof version);
    if (!is) damaged("the file is truncated");
    if (version != checkpoint_version)
      throw error(error_code::io_error, "checkpoint version " + std::to_string(version) +
                                            " cannot be read; this pradis reads version " +
                                            std::to_string(checkpoint_version));
    is.read(reinterpret_cast<char*>(&n), sizeof n);
    if (!is) damaged("the file is truncated");
    if (n > (std::uint64_t{1} << 40)) damaged("its payload length " + std::to_string(n) + " is implausible");
    // Read in chunks, so that a damaged length does not allocate the whole claim at once.
    constexpr std::uint64_t chunk = 1u << 20;
    while (buf_.size() < n) {
      const std::uint64_t k = std::min(chunk, n - buf_.size());
      const std::size_t old = buf_.size();
      buf_.resize(old + k);
      is.read(buf_.data() + old, static_cast<std::streamsize>(k));
      if (!is) damaged("the file is truncated");
    }
    is.read(reinterpret_cast<char*>(&sum), sizeof sum);
    if (!is) damaged("the file is truncated");
    if (sum != fnv1a(buf_.data(), buf_.size())) damaged("the checksum does not match its contents");
  }
  std::int64_t get_int() {
    std::int64_t x;
    raw(&x, sizeof x);
    return x;
  }
  double get_double() {
    double x;
    raw(&x, sizeof x);
    return x;
  }
  /// Reads a vector that must have `expected` entries (the model's size).
  template <class V>
  void get_vector(V& v, std::string_view what) {
    const std::int64_t n = get_int();
    if (n != static_cast<std::int64_t>(v.size()))
      throw error(error_code::io_error, "the checkpoint does not match the model's sizes (" + std::string(what) +
                                            ": " + std::to_string(n) + " values, the model has " +
                                            std::to_string(v.size()) + ")");
    raw(v.data(), static_cast<std::size_t>(n) * sizeof(double));
  }
  /// True when every field was read.
  bool at_end() const noexcept { return pos_ == buf_.size(); }
  [[noreturn]] static void damaged(const std::string& why) {
    throw error(error_code::io_error, "checkpoint damaged: " + why);
  }

 private:
  void raw(void* p, std::size_t n) {
    if (n > buf_.size() - pos_) damaged("a field runs past the end of its payload");
    if (n > 0) std::memcpy(p, buf_.data() + pos_, n);  // an empty vector's data() may be null
    pos_ += n;
  }
  std::string buf_;
  std::size_t pos_ = 0;
};

}  // namespace detail

/// A fingerprint of a model's topology: DOF count, element types, instance
/// names, connections, parameter counts and vector sizes, and the nodes of each
/// node kind (its label, their count and DOFs) (FNV-1a, 64 bit).
template <class Model>
std::uint64_t model_fingerprint(const Model& m) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* p, std::size_t n) { h = detail::fnv1a(p, n, h); };
  const int nd = m.dof_count();
  mix(&nd, sizeof nd);
  m.for_each_instances([&](const auto& vec) {
    for (const auto& in : vec) {
      using E = std::remove_cvref_t<decltype(in.element)>;
      mix(E::passport.name.data(), E::passport.name.size());
      mix(in.name.data(), in.name.size());
      mix(in.dofs.data(), sizeof(int) * in.dofs.size());
      mix(&in.npar, sizeof in.npar);
      mix(&in.work_size, sizeof in.work_size);
      mix(&in.state_size, sizeof in.state_size);
    }
  });
  m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
    mix(K::label.data(), K::label.size());
    const std::size_t count = nodes.size();
    mix(&count, sizeof count);
    for (const auto& node : nodes)
      for (std::size_t k = 0; k < static_cast<std::size_t>(K::size); ++k) {
        const int d = node.dofs[k];
        mix(&d, sizeof d);
      }
  });
  return h;
}

/// What a checkpoint holds besides the model fingerprint.
struct checkpoint_data {
  double time = 0;        ///< the time reached
  double h_nominal = 0;   ///< the nominal step of the next step
  double h_previous = 0;  ///< the last accepted step (error predictor)
  int successes = 0;      ///< successive full steps towards the next doubling (0..3)
  run_statistics stats;   ///< cumulative statistics
  global_state state;     ///< u, v, a, p of all DOFs
  Eigen::VectorXd a_previous;  ///< accelerations at the start of the last step (error predictor)
  std::vector<double> work, old_state, new_state;  ///< the model's pools
  /// Per DOF, its class found at the zero step: 3 the multiplier of an index-3 constraint, 1 an equation with neither
  /// mass nor viscosity, 2 such an equation whose DOF's velocity some equation reads (a source current), 0 any other
  /// (driver_core::dof_classes).
  std::vector<double> dof_classes;
};

/// Writes a checkpoint (version 5) of a model with the given fingerprint.
inline void write_checkpoint(std::ostream& os, std::uint64_t fingerprint, const checkpoint_data& c) {
  detail::checkpoint_writer w;
  w.put_int(static_cast<std::int64_t>(fingerprint));
  w.put_double(c.time);
  w.put_double(c.h_nominal);
  w.put_int(c.successes);
  const run_statistics& st = c.stats;
  for (long x : {st.steps, st.rejected_steps, st.newton_iterations, st.factorizations, st.evaluations,
                 st.error_rejections, st.jacobian_evaluations, st.jacobian_retries})
    w.put_int(x);
  w.put_int(st.last_iterations);
  w.put_double(st.last_step);
  w.put_int(st.limiting_dof);
  for (const auto* v : {&c.state.u, &c.state.v, &c.state.a, &c.state.p})
    w.put_vector({v->data(), static_cast<std::size_t>(v->size())});
  w.put_double(c.h_previous);
  w.put_vector({c.a_previous.data(), static_cast<std::size_t>(c.a_previous.size())});
  w.put_vector(c.work);
  w.put_vector(c.old_state);
  w.put_vector(c.new_state);
  w.put_vector(c.dof_classes);
  w.write(os);
}

/// Reads a checkpoint of a model with the given fingerprint, DOF count and pool
/// sizes (work, old state, new state), checking every
/// value: a finite time and potentials, steps >= 0, counts >= 0, sizes of the
/// model. Throws io_error ("checkpoint damaged: ..." and others) otherwise.
inline checkpoint_data read_checkpoint(std::istream& is, std::uint64_t fingerprint, int dofs, std::size_t work_size,
                                       std::size_t old_size, std::size_t new_size) {
  detail::checkpoint_reader r(is);
  if (static_cast<std::uint64_t>(r.get_int()) != fingerprint)
    throw error(error_code::io_error,
                "the checkpoint belongs to a different model (its DOFs, elements or connections differ)");
  auto damaged = [](const std::string& why) { detail::checkpoint_reader::damaged(why); };
  checkpoint_data c;
  c.time = r.get_double();
  c.h_nominal = r.get_double();
  const std::int64_t succ = r.get_int();
  if (!std::isfinite(c.time)) damaged("its time is not finite");
  if (!(std::isfinite(c.h_nominal) && c.h_nominal >= 0)) damaged("its step is not a finite number >= 0");
  if (succ < 0 || succ > 3) damaged("its count of successful steps " + std::to_string(succ) + " is out of range");
  c.successes = static_cast<int>(succ);
  run_statistics& st = c.stats;
  for (long* x : {&st.steps, &st.rejected_steps, &st.newton_iterations, &st.factorizations, &st.evaluations,
                  &st.error_rejections, &st.jacobian_evaluations, &st.jacobian_retries}) {
    const std::int64_t n = r.get_int();
    if (n < 0) damaged("a negative count in its statistics (" + std::to_string(n) + ")");
    *x = static_cast<long>(n);
  }
  const std::int64_t it = r.get_int();
  st.last_step = r.get_double();
  const std::int64_t lim = r.get_int();
  if (it < 0 || it > 1000000 || !(std::isfinite(st.last_step) && st.last_step >= 0) || lim < -1 || lim >= dofs)
    damaged("its statistics of the last step are out of range");
  st.last_iterations = static_cast<int>(it);
  st.limiting_dof = static_cast<int>(lim);
  c.state.resize(dofs);
  r.get_vector(c.state.u, "displacements");
  r.get_vector(c.state.v, "velocities");
  r.get_vector(c.state.a, "accelerations");
  r.get_vector(c.state.p, "pseudo-accelerations");
  if (!(c.state.u.allFinite() && c.state.v.allFinite() && c.state.a.allFinite() && c.state.p.allFinite()))
    damaged("a potential is not finite");
  c.h_previous = r.get_double();
  if (!(std::isfinite(c.h_previous) && c.h_previous >= 0)) damaged("its previous step is not a finite number >= 0");
  c.a_previous.resize(dofs);
  r.get_vector(c.a_previous, "previous accelerations");
  c.work.resize(work_size);
  c.old_state.resize(old_size);
  c.new_state.resize(new_size);
  r.get_vector(c.work, "work vectors");
  r.get_vector(c.old_state, "old state vectors");
  r.get_vector(c.new_state, "new state vectors");
  c.dof_classes.resize(static_cast<std::size_t>(dofs));
  r.get_vector(c.dof_classes, "DOF classes");
  for (const double k : c.dof_classes)
    if (k != 0 && k != 1 && k != 2 && k != 3) damaged("a DOF class is out of range");
  if (!r.at_end()) damaged("its payload has unread fields");
  return c;
}

/// A driver whose state another driver can take over (continue_from()): simulation and bdf_simulation.
template <class D>
concept CheckpointSource = requires(const D& d) {
  { d.checkpoint() } -> std::same_as<checkpoint_data>;
  { d.model_fingerprint() } -> std::same_as<std::uint64_t>;
};

/// The checks of a driver's continue_from(): the checkpoint data `c` of a driver of a model with fingerprint `from`
/// fits a driver of a model with fingerprint `to`, `dofs` DOFs and the pool sizes (work, old state, new state).
/// Throws invalid_option otherwise (another model, or pools sized by other parameters).
inline void check_handover(const checkpoint_data& c, std::uint64_t from, std::uint64_t to, int dofs,
                           std::size_t work_size, std::size_t old_size, std::size_t new_size) {
  if (from != to)
    throw error(error_code::invalid_option,
                "cannot continue from a driver of a different model (its DOFs, elements or connections differ)");
  if (c.state.u.size() != dofs || c.work.size() != work_size || c.old_state.size() != old_size ||
      c.new_state.size() != new_size)
    throw error(error_code::invalid_option,
                "cannot continue from that driver: its model's DOFs or element work and state vectors have other "
                "sizes");
}

}  // namespace pradis
