// What a scene is about, for the window's description panel: the comment block a scene file
// opens with (the shipped scenes explain there what they teach), else its scene.description.
// No GL; internal to src/app/.
#pragma once

#include <string>

namespace periflex {

// The leading comment block of TOML text: the lines that start with '#' before the first line
// that is neither a comment nor blank, without the '#' and one space after it. The lines of a
// paragraph are joined with spaces (the panel wraps them to its width); an empty comment line
// ends a paragraph, and an indented line (a command, say) keeps a line of its own. A line of
// only '-', '=' or '#' (a ruler) is left out.
// Empty when the text does not open with a comment.
std::string leading_comment(const std::string& toml_text);

// The description shown for a scene file: its leading comment, else `description` (the
// scene.description key), else "".
std::string scene_description(const std::string& path, const std::string& description);

}  // namespace periflex
