// Every rejected call throws InvalidArgument before it changes anything: the world is left
// exactly as it was. The message names the call, the field and the value.
#pragma once

#include <stdexcept>
#include <string>

namespace softstep {

class InvalidArgument : public std::invalid_argument {
 public:
  InvalidArgument(std::string field, const std::string& message)
      : std::invalid_argument(message), field_(std::move(field)) {}
  // The offending field as the caller spells it, e.g. "BodyDef.mass" or "body_b".
  const std::string& field() const noexcept { return field_; }

 private:
  std::string field_;
};

}  // namespace softstep
