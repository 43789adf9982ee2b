// Builds the contact kernel table of one lane type. Included only by the
// contact_kernels_<width>.cpp files, each compiled for its instruction set; nothing else
// belongs in those files (see solver/kernel_table.hpp for why).
#pragma once

#include <utility>

#include "contacts/contact_kernels.hpp"

namespace softstep::solver {

template <class L>
ContactKernels<simd::kWidth<L>> make_contact_kernels() {
  using K = ContactKernels<simd::kWidth<L>>;
  using Group = typename K::Group;
  K k;
  [&]<std::uint32_t... S>(std::integer_sequence<std::uint32_t, S...>) {
    ((k.prepare[S] = [](Group* g, std::size_t n, const simd::BodyArrays& b,
                        const simd::SubstepContext&, const simd::ContactContext&) {
        for (std::size_t i = 0; i < n; ++i) simd::prepare_contacts<L, S>(g[i], b);
      }),
     ...);
    ((k.warm_start[S] = [](Group* g, std::size_t n, const simd::BodyArrays& b,
                           const simd::SubstepContext&, const simd::ContactContext&) {
        for (std::size_t i = 0; i < n; ++i) simd::warm_start_contacts<L, S>(g[i], b);
      }),
     ...);
    ((k.solve[S] = [](Group* g, std::size_t n, const simd::BodyArrays& b,
                      const simd::SubstepContext& ctx, const simd::ContactContext& cc) {
        for (std::size_t i = 0; i < n; ++i) simd::solve_contacts<L, S, true>(g[i], b, ctx, cc);
      }),
     ...);
    ((k.relax[S] = [](Group* g, std::size_t n, const simd::BodyArrays& b,
                      const simd::SubstepContext& ctx, const simd::ContactContext& cc) {
        for (std::size_t i = 0; i < n; ++i) simd::solve_contacts<L, S, false>(g[i], b, ctx, cc);
      }),
     ...);
  }(std::make_integer_sequence<std::uint32_t, simd::kContactSignatures>());
  k.restitute = [](Group* g, std::size_t n, const simd::BodyArrays& b,
                   const simd::SubstepContext&, const simd::ContactContext& cc) {
    for (std::size_t i = 0; i < n; ++i) simd::restitute_contacts<L>(g[i], b, cc);
  };
  return k;
}

}  // namespace softstep::solver
