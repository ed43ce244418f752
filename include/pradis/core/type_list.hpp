#pragma once
/// \file
/// Minimal compile-time type list utilities used for element catalogs.

#include <cstddef>
#include <type_traits>

namespace pradis {

/// A list of types.
template <class... Ts>
struct type_list {
  static constexpr std::size_t size = sizeof...(Ts);
};

/// Whether T is one of Ts.
template <class T, class... Ts>
inline constexpr bool contains_v = (std::is_same_v<T, Ts> || ...);

/// Whether all of Ts are distinct.
template <class... Ts>
inline constexpr bool distinct_v = true;
template <class T, class... Ts>
inline constexpr bool distinct_v<T, Ts...> = (!contains_v<T, Ts...>)&&distinct_v<Ts...>;

/// Index of T in Ts (requires contains_v<T, Ts...>).
template <class T, class... Ts>
constexpr std::size_t index_of() {
  constexpr bool hits[] = {std::is_same_v<T, Ts>...};
  for (std::size_t i = 0; i < sizeof...(Ts); ++i)
    if (hits[i]) return i;
  return sizeof...(Ts);
}

/// Concatenation of type lists.
template <class... Ls>
struct concat;
template <class... A>
struct concat<type_list<A...>> {
  using type = type_list<A...>;
};
template <class... A, class... B, class... Rest>
struct concat<type_list<A...>, type_list<B...>, Rest...> {
  using type = typename concat<type_list<A..., B...>, Rest...>::type;
};
template <class... Ls>
using concat_t = typename concat<Ls...>::type;

/// Applies a template to the types of a list: apply_t<model, type_list<A, B>> is model<A, B>.
template <template <class...> class T, class L>
struct apply;
template <template <class...> class T, class... A>
struct apply<T, type_list<A...>> {
  using type = T<A...>;
};
template <template <class...> class T, class L>
using apply_t = typename apply<T, L>::type;

/// A type list without repeats (the first of each kept): unique_t<type_list<A, B, A>> is type_list<A, B>.
template <class Done, class... Rest>
struct unique_impl {
  using type = Done;
};
template <class... D, class T, class... Rest>
struct unique_impl<type_list<D...>, T, Rest...> {
  using type = typename unique_impl<std::conditional_t<contains_v<T, D...>, type_list<D...>, type_list<D..., T>>,
                                    Rest...>::type;
};
template <class L>
struct unique;
template <class... Ts>
struct unique<type_list<Ts...>> {
  using type = typename unique_impl<type_list<>, Ts...>::type;
};
template <class L>
using unique_t = typename unique<L>::type;

}  // namespace pradis
