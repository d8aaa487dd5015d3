/// @file fuzz/fuzz_scene.cpp
/// libFuzzer target: vm::parse_scene on any text, then each phase evaluated at
/// the domain's centre (expressions are compiled lazily by muparser, so a bad
/// one may only fail there). The source names a file in the fuzzer's empty
/// folder, where "grid" phases look for their files.

#include "input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    vm::fuzz::evaluate_at_centre(vm::parse_scene(text, (vm::fuzz::input_folder() / "scene.json").string()));
  } catch (const vm::Error&) {
  }
  return 0;
}
