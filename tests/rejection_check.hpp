// The house check of a rejected call (validation_test.cpp, joints/joint_validation_test.cpp):
// on a fresh fixture, `call` must throw InvalidArgument whose field() is `field` and whose
// message shows `value`, and leave the world's full state (state_hash) as it was.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "softstep/errors.hpp"

namespace softstep::test {

template <class Fixture>
void expect_rejected_on(const std::function<Fixture()>& make,
                        const std::function<void(Fixture&)>& call, const std::string& field,
                        const std::string& value) {
  Fixture f = make();
  const std::uint64_t before = f.world.state_hash();
  try {
    call(f);
    ADD_FAILURE() << "accepted; expected rejection of " << field;
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find(value), std::string::npos)
        << "message '" << e.what() << "' should show the value " << value;
  }
  EXPECT_EQ(f.world.state_hash(), before) << "world changed by a rejected call on " << field;
}

}  // namespace softstep::test
