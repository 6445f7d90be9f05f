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

// A library's message (tinyobjloader's, OpenImageIO's), which may end in or hold
// newlines, as part of a SceneError's one line.
inline std::string one_line(const std::string& message) {
    std::string out;
    for (char c : message) {
        if (c == '\n' || c == '\r') {
            if (!out.empty() && out.back() != ' ') out += ' ';
        } else {
            out += c;
        }
    }
    while (!out.empty() && out.back() == ' ') out.pop_back();
    return out;
}

}  // namespace vkrt
