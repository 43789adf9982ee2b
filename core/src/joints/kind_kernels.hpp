// Builds one kind's kernel table at one lane type. Included only by the generated
// <kind>_kernels_<width>.cpp files (core/CMakeLists.txt, kind_kernels.cpp.in), each compiled
// for its instruction set; nothing else belongs in those files (an inline function compiled
// with AVX2 there could be the copy the linker keeps for scalar callers).
#pragma once

#include <utility>

#include "joints/joint_kind.hpp"

namespace softstep {

template <class Kind, class L, std::size_t V>
PassKernels<typename Kind::template Group<simd::kWidth<L>>> variant_kernels() {
  using Group = typename Kind::template Group<simd::kWidth<L>>;
  PassKernels<Group> k{};
  k.prepare = [](Group* g, std::size_t n, const simd::BodyArrays& b,
                 const simd::SubstepContext& ctx, std::uint32_t sig) {
    for (std::size_t i = 0; i < n; ++i) Kind::template prepare<L, V>(g[i], b, ctx, sig);
  };
  if constexpr (Kind::solves(V)) {
    k.warm_start = [](Group* g, std::size_t n, const simd::BodyArrays& b,
                      const simd::SubstepContext& ctx, std::uint32_t sig) {
      for (std::size_t i = 0; i < n; ++i) Kind::template warm_start<L, V>(g[i], b, ctx, sig);
    };
    k.solve = [](Group* g, std::size_t n, const simd::BodyArrays& b,
                 const simd::SubstepContext& ctx, std::uint32_t sig) {
      for (std::size_t i = 0; i < n; ++i) Kind::template solve<L, V, true>(g[i], b, ctx, sig);
    };
  }
  if constexpr (Kind::relaxes(V)) {
    k.relax = [](Group* g, std::size_t n, const simd::BodyArrays& b,
                 const simd::SubstepContext& ctx, std::uint32_t sig) {
      for (std::size_t i = 0; i < n; ++i) Kind::template solve<L, V, false>(g[i], b, ctx, sig);
    };
  }
  return k;
}

template <class Kind, class L>
KindKernels<Kind, simd::kWidth<L>> build_kind_kernels() {
  return [&]<std::size_t... V>(std::index_sequence<V...>) {
    return KindKernels<Kind, simd::kWidth<L>>{variant_kernels<Kind, L, V>()...};
  }
  (std::make_index_sequence<Kind::variants.size()>());
}

}  // namespace softstep
