// One line of text that never runs past its window: cut to the room left with an ellipsis, the
// whole line in a tooltip when the mouse is over it (the status bar, long names in panels).
#pragma once
#include <string>

namespace gb {

// Draws `text` at the cursor in at most the width left on the line; true when it had to be cut.
bool fittedText(const std::string& text);

// `text` cut (at a UTF-8 character boundary) so that it and "..." measure at most `width` pixels
// with the current font; `text` itself when it fits.
std::string fitToWidth(const std::string& text, float width);

}  // namespace gb
