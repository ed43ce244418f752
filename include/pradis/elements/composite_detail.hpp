#pragma once
/// \file
/// Compile-time machinery of the composite super-element (composite.hpp): the passport derived from the
/// parts, the rotational nodes mapped and checked, and the help text assembled from the parts' help.
/// docs/super-elements.md.

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <string_view>

#include <Eigen/Core>

#include "pradis/core/domain.hpp"
#include "pradis/core/element.hpp"

namespace pradis {

/// One part of a composite super-element: the element type E and, for each of E's local DOFs (EXT + ENT, in
/// E's order, hidden q4 slots included), the composite's local DOF it is connected to (0..EXT-1 the
/// composite's external DOFs, EXT..EXT+ENT-1 its internal DOFs). Example: the BEAM3 from the composite's node
/// A (DOFs 0..5, q4 at 12) to an inner node (14..19, q4 at 20): `part<elastic_beam, 0, 1, 2, 3, 4, 5, 14, 15,
/// 16, 17, 18, 19, 12, 20>`.
template <class E, int... Local>
struct part {
  static_assert(HasPassport<E>, "pradis: a part of a composite must be an element type (it has no passport)");
  static_assert(sizeof...(Local) == element_traits<E>::n,
                "pradis: a part's map must give one composite DOF for each local DOF of the part (its EXT + ENT, "
                "hidden q4 slots included)");
  /// The part's element type.
  using element = E;
  /// Composite local DOF of each of the part's local DOFs.
  static constexpr std::array<int, sizeof...(Local)> map{Local...};
};

namespace composite_detail {

/// Whether E has the commit hook.
template <class E>
concept has_commit = requires(E& e, element_context& c) {
  e.commit(c);
};
/// Whether E restricts the states the checks may use.
template <class E>
concept has_admissible = requires(const E& e, const local_input<E>& i) {
  { e.admissible(i) } -> std::convertible_to<bool>;
};

/// The drawer a part's draw hook receives inside a composite: the part's local
/// DOFs and rotational nodes are mapped to the composite's, then drawn with the
/// composite's drawer (io/model_scene.hpp, element_drawer).
template <class Drawer, class P>
struct part_drawer {
  Drawer& d;
  static constexpr auto& map = P::map;
  static constexpr int at(int k) { return map[static_cast<std::size_t>(k)]; }
  /// A point moving with the part's translational DOFs k, k+1, k+2.
  int point(const Eigen::Vector3d& x0, int k) {
    return d.point_at(x0, {at(k), at(k + 1), at(k + 2)});
  }
  /// A point of the body of the part's rotational node `node`.
  int body_point(const Eigen::Vector3d& x0, int k, int node, const Eigen::Vector3d& offset) {
    const rotation_slot s = P::element::rotation_nodes.at(static_cast<std::size_t>(node));
    return d.body_point_at(x0, {at(k), at(k + 1), at(k + 2)}, rotation_slot{at(s.q1), at(s.q4)}, offset);
  }
  void vertex(int a) { d.vertex(a); }
  void line(int a, int b) { d.line(a, b); }
  void triangle(int a, int b, int c) { d.triangle(a, b, c); }
};

/// The passport keys the parts add up to.
struct sums {
  int par = 0, str = 0, wrk = 0;
  bool k = false, c = false, m = false;
};

template <class... Ps>
constexpr sums sum_of() {
  sums s;
  ((s.par += Ps::element::passport.par, s.str += Ps::element::passport.str, s.wrk += Ps::element::passport.wrk,
    s.k = s.k || Ps::element::passport.has_k(), s.c = s.c || Ps::element::passport.has_c(),
    s.m = s.m || Ps::element::passport.has_m()),
   ...);
  return s;
}

/// ADR/IGN that declare exactly the blocks present in at least one part (M is kept if no part declares any
/// block: ADR = 3 needs it).
constexpr std::array<int, 2> adr_ign(bool k, bool c, bool m) {
  if (k) return {1, (c ? 0 : 2) + (m ? 0 : 3) == 5 ? 23 : (c ? 0 : 2) + (m ? 0 : 3)};
  if (c) return {2, m ? 0 : 3};
  return {3, 0};
}

/// Prefix sums: offset of part i in a concatenation of sizes.
template <std::size_t P>
constexpr std::array<int, P + 1> offsets(const std::array<int, P>& sizes) {
  std::array<int, P + 1> o{};
  for (std::size_t i = 0; i < P; ++i) o[i + 1] = o[i] + sizes[i];
  return o;
}

/// Checks the parts' maps: in range, a part's local DOFs on distinct composite DOFs, every composite DOF used
/// by some part, the parts' external DOFs not on internal slots that another part uses as a hidden q4.
/// nullptr when valid.
template <class... Ps>
constexpr const char* map_problem(int ext, int ent) {
  const int n = ext + ent;
  const char* problem = nullptr;
  std::array<bool, 512> used{};
  if (n > 512) return "a composite may have at most 512 local DOFs";
  (
      [&] {
        constexpr auto& mp = Ps::map;
        for (std::size_t r = 0; r < mp.size(); ++r) {
          if (mp[r] < 0 || mp[r] >= n) {
            if (!problem) problem = "a part's map names a composite DOF outside 0 .. EXT + ENT - 1";
            return;
          }
          used[static_cast<std::size_t>(mp[r])] = true;
          for (std::size_t q = 0; q < r; ++q)
            if (mp[q] == mp[r] && !problem)
              problem = "a part's map connects two of its local DOFs to the same composite DOF";
        }
      }(),
      ...);
  if (problem) return problem;
  for (int k = 0; k < n; ++k)
    if (!used[static_cast<std::size_t>(k)])
      return "a composite DOF is connected to no part (its equation would be empty)";
  return nullptr;
}

/// The rotational nodes of the composite: the parts' slots mapped, deduplicated, in order of first
/// appearance, with the number found and the first problem.
struct rotation_table {
  std::array<rotation_slot, 128> slots{};
  int count = 0;
  const char* problem = nullptr;
};

template <class... Ps>
constexpr rotation_table rotation_table_of() {
  rotation_table t;
  (
      [&] {
        constexpr auto rs = element_traits<typename Ps::element>::rotation_nodes;
        constexpr auto& mp = Ps::map;
        for (const rotation_slot& s : rs) {
          const auto q1 = static_cast<std::size_t>(s.q1);
          const rotation_slot m{mp[q1], mp[static_cast<std::size_t>(s.q4)]};
          if (mp[q1 + 1] != m.q1 + 1 || mp[q1 + 2] != m.q1 + 2) {
            if (!t.problem) t.problem = "a part's rotational node must map q1, q2, q3 to consecutive composite DOFs";
            continue;
          }
          bool seen = false;
          for (int i = 0; i < t.count; ++i) {
            const rotation_slot& o = t.slots[static_cast<std::size_t>(i)];
            if (o == m)
              seen = true;
            else if ((o.q1 == m.q1 || o.q4 == m.q4) && !t.problem)
              t.problem = "two parts map the same rotational node's q1..q3 and q4 inconsistently";
          }
          if (!seen && t.count < 128) t.slots[static_cast<std::size_t>(t.count++)] = m;
        }
      }(),
      ...);
  return t;
}

/// The physical domain of every composite DOF: the one the parts declare on it (core/domain.hpp), unspecified
/// if none does; `conflict` if two parts disagree.
struct domain_table {
  std::array<domain, 512> dom{};
  bool conflict = false;
};

template <class... Ps>
constexpr domain_table domain_table_of() {
  domain_table t;
  (
      [&] {
        for (std::size_t k = 0; k < Ps::map.size(); ++k) {
          const domain d = declared_domain<typename Ps::element>(static_cast<int>(k));
          auto& have = t.dom[static_cast<std::size_t>(Ps::map[k])];
          if (d == domain::unspecified) continue;
          if (have != domain::unspecified && have != d) t.conflict = true;
          have = d;
        }
      }(),
      ...);
  return t;
}

// ---- help text --------------------------------------------------------------

/// A text built in a constant expression (help texts of composites). Not
/// std::string: clang 14 with libstdc++ 12 cannot evaluate std::string's
/// small-buffer union at compile time; and not std::vector<char>, which GCC
/// evaluates too slowly for the long parameter lists of a crank throw.
class text {
 public:
  constexpr text() = default;
  constexpr text(std::string_view s) { append(s.data(), s.size()); }
  constexpr text(const char* s) : text(std::string_view(s)) {}
  constexpr text(const text& o) { append(o.d_, o.n_); }
  constexpr text(text&& o) noexcept : d_(o.d_), n_(o.n_), cap_(o.cap_) { o.d_ = nullptr, o.n_ = o.cap_ = 0; }
  constexpr text& operator=(text o) noexcept {
    std::swap(d_, o.d_), std::swap(n_, o.n_), std::swap(cap_, o.cap_);
    return *this;
  }
  constexpr ~text() { delete[] d_; }
  constexpr text& operator+=(const text& o) {
    append(o.d_, o.n_);
    return *this;
  }
  friend constexpr text operator+(text a, const text& b) { return std::move(a += b); }
  friend constexpr text operator+(const char* a, const text& b) { return std::move(text(a) += b); }
  constexpr bool empty() const { return n_ == 0; }
  constexpr std::size_t size() const { return n_; }
  constexpr char& back() { return d_[n_ - 1]; }
  constexpr void pop_back() { --n_; }
  constexpr void push_front(char x) {
    reserve(n_ + 1);
    for (std::size_t i = n_; i > 0; --i) d_[i] = d_[i - 1];
    d_[0] = x, ++n_;
  }
  constexpr text substr(std::size_t from) const { return text(std::string_view(d_ + from, n_ - from)); }
  constexpr const char* begin() const { return d_; }
  constexpr const char* end() const { return d_ + n_; }
  /// The text as a run-time string (messages).
  std::string str() const { return std::string(begin(), end()); }

 private:
  constexpr void reserve(std::size_t n) {
    if (n <= cap_) return;
    const std::size_t cap = n > 2 * cap_ ? n : 2 * cap_;
    char* d = new char[cap];
    for (std::size_t i = 0; i < n_; ++i) d[i] = d_[i];
    delete[] d_;
    d_ = d, cap_ = cap;
  }
  constexpr void append(const char* s, std::size_t n) {
    reserve(n_ + n);
    for (std::size_t i = 0; i < n; ++i) d_[n_ + i] = s[i];
    n_ += n;
  }
  char* d_ = nullptr;
  std::size_t n_ = 0, cap_ = 0;
};

constexpr text number(int k) {
  text s;
  if (k == 0) return "0";
  while (k > 0) {
    s.push_front(static_cast<char>('0' + k % 10));
    k /= 10;
  }
  return s;
}

/// Line j (0-based) of a '\n'-separated help list without its "N - " prefix, or "".
constexpr text line_of(std::string_view list, int j) {
  int at = 0;
  std::size_t b = 0;
  while (at < j) {
    const std::size_t e = list.find('\n', b);
    if (e == std::string_view::npos) return {};
    b = e + 1;
    ++at;
  }
  if (b >= list.size()) return {};
  std::size_t e = list.find('\n', b);
  if (e == std::string_view::npos) e = list.size();
  std::string_view l = list.substr(b, e - b);
  std::size_t d = 0;
  while (d < l.size() && l[d] >= '0' && l[d] <= '9') ++d;
  if (d > 0 && l.substr(d).starts_with(" - ")) l = l.substr(d + 3);
  return text(l);
}

/// "part i 'NAME' (label)".
template <class Spec, class P>
constexpr text part_name(int i) {
  text s = "part " + number(i + 1) + " '" + text(P::element::passport.name) + "'";
  if constexpr (requires { Spec::labels; }) s += " (" + text(Spec::labels[static_cast<std::size_t>(i)]) + ")";
  return s;
}

/// The parameter list: one line per PAR entry, naming its part.
template <class Spec, class... Ps>
constexpr text parameter_text() {
  text s;
  int k = 0, i = 0;
  (
      [&] {
        for (int j = 0; j < Ps::element::passport.par; ++j) {
          text l = line_of(Ps::element::help.parameters, j);
          if (l.empty()) l = "parameter " + number(j + 1);
          s += number(++k) + " - " + part_name<Spec, Ps>(i) + ", its parameter " + number(j + 1) + ": " + l + "\n";
        }
        ++i;
      }(),
      ...);
  if (!s.empty()) s.pop_back();
  return s;
}

/// The external DOF list: each composite DOF described by the first part that uses it.
template <class Spec, class... Ps>
constexpr text dof_text(int ext) {
  text s;
  for (int k = 0; k < ext; ++k) {
    text l;
    int i = 0;
    (
        [&] {
          for (std::size_t r = 0; r < Ps::map.size() && l.empty(); ++r)
            if (Ps::map[r] == k && static_cast<int>(r) < Ps::element::passport.ext) {
              l = line_of(Ps::element::help.dofs, static_cast<int>(r));
              if (l.empty()) l = "DOF " + number(static_cast<int>(r) + 1);
              l += " (" + part_name<Spec, Ps>(i) + ", its DOF " + number(static_cast<int>(r) + 1) + ")";
            }
          ++i;
        }(),
        ...);
    if (l.empty()) l = "internal DOF of the parts";
    s += number(k + 1) + " - " + l + "\n";
  }
  if (!s.empty()) s.pop_back();
  return s;
}

/// The work list: the parts' entries, then the statistics.
template <class Spec, class... Ps>
constexpr text work_text() {
  text s;
  int k = 0, i = 0;
  (
      [&] {
        for (int j = 0; j < Ps::element::passport.wrk; ++j) {
          text l = line_of(Ps::element::help.work, j);
          if (l.empty()) l = "work entry " + number(j + 1);
          s += number(++k) + " - " + part_name<Spec, Ps>(i) + ": " + l + "\n";
        }
        ++i;
      }(),
      ...);
  s += number(++k) + " - evaluations of this instance (every part is evaluated once per evaluation) [-]\n";
  i = 0;
  ((s += number(++k) + " - errors raised by " + part_name<Spec, Ps>(i++) + " (code 75 cuts the step) [-]\n"), ...);
  s.pop_back();
  return s;
}

/// The name line: "Super-element of N parts: BEAM3, BEAMI3, ...".
template <class... Ps>
constexpr text name_text() {
  text s = "Super-element of " + number(static_cast<int>(sizeof...(Ps))) + " parts:";
  ((s += " " + text(Ps::element::passport.name) + ","), ...);
  s.back() = '.';
  return s;
}

/// Storage for a text computed at compile time: `text_storage<F>::view` is a string_view into a static array
/// holding F()().
template <class F>
struct text_storage {
  static constexpr std::size_t size = F{}().size();
  static constexpr std::array<char, size + 1> chars = [] {
    std::array<char, size + 1> a{};
    const text s = F{}();
    std::copy(s.begin(), s.end(), a.begin());
    return a;
  }();
  static constexpr std::string_view view{chars.data(), size};
};

}  // namespace composite_detail
}  // namespace pradis
