#pragma once
// The one error type for bad input. Its message is complete and user-facing:
// "<file>: <json path or line>: <what was expected>" (docs/architecture.md, principle 5).
#include <stdexcept>
#include <string>

namespace vkrt {

class SceneError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace vkrt
