// The check every rejection test makes: the call throws InvalidArgument whose field() is
// `field` and whose message shows `value`. (Whether the world is unchanged is the caller's
// to check: it knows which world.)
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "softstep/errors.hpp"

namespace softstep {

inline void expect_invalid_argument(const std::function<void()>& call, const std::string& field,
                                    const std::string& value) {
  try {
    call();
    ADD_FAILURE() << "accepted; expected rejection of " << field;
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find(value), std::string::npos)
        << "message '" << e.what() << "' should show " << value;
  }
}

}  // namespace softstep
