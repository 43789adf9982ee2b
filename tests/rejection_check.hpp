// The house check of a rejected call (validation_test.cpp, joints/joint_validation_test.cpp):
// on a fresh fixture, `call` must be rejected as expect_invalid_argument.hpp checks (field
// and value), and leave the world's full state (state_hash) as it was.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "expect_invalid_argument.hpp"

namespace softstep::test {

template <class Fixture>
void expect_rejected_on(const std::function<Fixture()>& make,
                        const std::function<void(Fixture&)>& call, const std::string& field,
                        const std::string& value) {
  Fixture f = make();
  const std::uint64_t before = f.world.state_hash();
  expect_invalid_argument([&] { call(f); }, field, value);
  EXPECT_EQ(f.world.state_hash(), before) << "world changed by a rejected call on " << field;
}

}  // namespace softstep::test
