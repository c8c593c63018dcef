// Every key and mouse action of the window, as the F1 help window lists them (docs/gui.md
// has the same table). Internal to src/app/.
#pragma once

#include <array>

namespace periflex {

struct KeyHelp {
  const char* input;
  const char* action;
};

inline constexpr std::array<KeyHelp, 21> kKeyHelp = {{
    {"F1", "show or hide this list"},
    {"Space", "run / pause"},
    {"Right arrow", "one step (pauses first; hold to repeat); in the history: one saved state forward"},
    {"Left arrow", "one saved state back in the history (pauses; hold to repeat)"},
    {"Backspace", "reset to t = 0 (keeps the live settings)"},
    {"F", "fit the view to the scene (and stop following a body)"},
    {"D", "undeformed shape, and back to the magnification before"},
    {"P", "show or hide the plot window (wheel: zoom, drag: pan, double-click: whole run)"},
    {"K", "knife on / off"},
    {"Left-drag with the knife on", "cut the bonds the segment crosses (live; Backspace resets)"},
    {"C", "draw the active contacts (a dot and a stroke along the force), or not"},
    {"S", "screenshot periflex_<scene>_t<time>.png in the current folder"},
    {"Ctrl+Q", "quit"},
    {"Right-drag", "pan"},
    {"Wheel", "zoom about the cursor"},
    {"Left-drag on a body or particle", "pull it with a spring towards the pointer (on a flexible body its anchor walks there at a speed the material follows)"},
    {"Shift + left-drag", "a hard pull: the anchor ten times faster, its force limit ten times higher"},
    {"Ctrl+click on a slider", "type its value"},
    {"Enter in a number field", "apply the value typed"},
    {"Pointer over a panel", "keys and mouse act on the panel, not the picture"},
    {"Saving the scene file", "reloads it (the view is kept; an error is shown, old scene kept)"},
}};

}  // namespace periflex
