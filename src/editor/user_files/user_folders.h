#pragma once
// Where the editor keeps files of its own between runs, following the XDG base directories:
// autosaved work under the state folder, the recent-files list under the config folder.
// PRIMO_STATE_DIR and PRIMO_CONFIG_DIR override them (tests, portable installs).

#include <string>

namespace primo::editor {

// $PRIMO_STATE_DIR, else $XDG_STATE_HOME/primo, else ~/.local/state/primo.
std::string state_folder();
// $PRIMO_CONFIG_DIR, else $XDG_CONFIG_HOME/primo, else ~/.config/primo.
std::string config_folder();

}  // namespace primo::editor
