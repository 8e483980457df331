// What a scene needs, decided once per run, so that the step kernels can be compiled without
// the features a scene does not use (an unused feature then costs nothing in the inner loops).
#pragma once

#include <string>
#include <type_traits>

namespace dem {

struct SceneFeatures {
  bool clumps = false;           ///< some body has two spheres (else: no rotation geometry)
  bool friction = false;         ///< grain-grain tangential springs
  bool wall_friction = false;    ///< grain-wall tangential springs
  bool gravity = false;
  bool local_damping = false;    ///< Cundall's non-viscous damping in the integrator
  bool viscous_damping = false;  ///< normal dashpot in the contacts
  bool rotation() const { return clumps || friction || wall_friction; }
  std::string describe() const;
};

/// Calls f(std::bool_constant<b1>{}, std::bool_constant<b2>{}, ...) for runtime flags b1, b2, ...
/// so a kernel templated on its features is chosen once, by table-free recursion, instead of a
/// hand-written ladder of instantiations.
template <typename F>
void with_flags(F&& f) {
  f();
}
template <typename F, typename... Flags>
void with_flags(F&& f, bool first, Flags... rest) {
  if (first)
    with_flags([&](auto... tail) { f(std::true_type{}, tail...); }, rest...);
  else
    with_flags([&](auto... tail) { f(std::false_type{}, tail...); }, rest...);
}

}  // namespace dem
