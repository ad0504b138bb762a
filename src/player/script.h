// The player's action script (`tspplay play --script FILE`): one action per line, for tests and
// demos, each a player Command (command.h). Format and behaviour: docs/player.md.
#pragma once
#include <string>
#include <vector>

#include "player/command.h"

namespace tspplayer {

/// One script line's command.
struct ScriptLine {
  Command command;  ///< what it asks for
  int line = 0;     ///< 1-based line in the script, for messages
};

/// Parses one script line's words (a line split at blanks, the action first) into its command,
/// checked by validate(). Throws tsp::FormatError "ORIGIN:LINE: what was expected".
Command parse_command(const std::vector<std::string>& words, const std::string& origin,
                      int line);

/// Parses script text; origin names it in messages. Blank lines and lines starting with '#' are
/// skipped. Throws tsp::FormatError naming origin, the line and what was expected.
std::vector<ScriptLine> parse_script(const std::string& text, const std::string& origin);
/// Reads (through tsp::read_input_file: a regular file of at most 64 MiB) and parses a script
/// file. Throws tsp::IoError when it is not such a file or unreadable, else like parse_script.
std::vector<ScriptLine> load_script(const std::string& path);

}  // namespace tspplayer
