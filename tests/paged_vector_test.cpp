// PagedVector (core/src/paged_vector.hpp): blocks of a huge page or more start on a huge page
// (the condition for Linux to back them with huge pages), smaller ones are ordinary, and the
// vector behaves as std::vector through growth. The world's per-body and per-joint records
// are held in it.
#include "paged_vector.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <type_traits>

#include "world_impl.hpp"

namespace softstep {
namespace {

std::uintptr_t offset_in_huge_page(const void* p) {
  return reinterpret_cast<std::uintptr_t>(p) % kHugePage;
}

TEST(PagedVector, BlocksOfAHugePageOrMoreStartOnAHugePage) {
  PagedVector<double> big(kHugePage / sizeof(double) + 1);
  EXPECT_EQ(offset_in_huge_page(big.data()), 0u);
  for (double x : big) ASSERT_EQ(x, 0.0);  // value-initialized, as std::vector
  // Growing from an ordinary block into a paged one keeps the elements.
  PagedVector<std::uint64_t> grown;
  const std::size_t count = 3 * kHugePage / sizeof(std::uint64_t);
  for (std::uint64_t i = 0; i < count; ++i) grown.push_back(i * 2654435761u);
  EXPECT_EQ(offset_in_huge_page(grown.data()), 0u);
  for (std::uint64_t i = 0; i < count; ++i) ASSERT_EQ(grown[i], i * 2654435761u);
  grown.resize(10);
  grown.shrink_to_fit();  // back to an ordinary block
  EXPECT_EQ(grown.size(), 10u);
  EXPECT_EQ(grown[9], std::uint64_t{9} * 2654435761u);
}

TEST(PagedVector, OverAlignedRecordsKeepTheirAlignmentInBothKindsOfBlock) {
  struct alignas(64) Lanes {
    float x[16];
  };
  const PagedVector<Lanes> small(3);
  const PagedVector<Lanes> big(kHugePage / sizeof(Lanes) + 1);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(small.data()) % 64, 0u);
  EXPECT_EQ(offset_in_huge_page(big.data()), 0u);
}

// The records a step walks are the ones on huge pages (a compile-time guard: swapping one back
// to std::vector fails to build this test).
static_assert(std::is_same_v<decltype(World::Impl::bodies), BodySlots>);
static_assert(std::is_same_v<decltype(World::Impl::joints), JointSlots>);
static_assert(std::is_same_v<decltype(SolverBodies::velocity), PagedVector<simd::VelocityRecord>>);

}  // namespace
}  // namespace softstep
