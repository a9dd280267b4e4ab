#pragma once
// Third-party libraries speak to the terminal on their own (libpng through OpenCV's decoders
// writes "libpng error: ..." to stderr; tinygltf's messages hold newlines). meadow's rule is one
// line per failure, so what they say is caught and folded into that line instead.
#include <string>
#include <string_view>

namespace meadow {

// While alive, whatever is written to the process's stderr (file descriptor 2) goes to a
// temporary file instead; text() returns it folded into one line. Not for use on several
// threads at once: it redirects the whole process's stderr.
class CapturedStderr {
public:
    CapturedStderr();
    CapturedStderr(const CapturedStderr&) = delete;
    CapturedStderr& operator=(const CapturedStderr&) = delete;
    ~CapturedStderr();
    // What was written so far, as one line ("" for nothing); restores stderr first.
    [[nodiscard]] std::string text();

private:
    void restore();
    int saved_ = -1;
    int file_ = -1;
};

// `text` with every run of line breaks and the white space around them turned into "; ", and
// the ends trimmed.
[[nodiscard]] std::string oneLine(std::string_view text);

}  // namespace meadow
