// Fuzz target: a player action script (src/player/script.*), read and parsed as `play --script`
// reads it (through the input gate); every action it yields must pass validate() again, the one
// check keys and panels share.
#include "fuzz_input.h"
#include "player/script.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = tspfuzz::write_input("input.script", data, size);
  tspfuzz::expect_clean([&] {
    for (const tspplayer::ScriptLine& a : tspplayer::load_script(path))
      tspplayer::validate(a.command);
  });
  return 0;
}
