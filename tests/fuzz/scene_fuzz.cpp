// libFuzzer target: scene files (ParseScene). Built and run by `make fuzz` (scripts/fuzz.sh).
#include "fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) { return aalab::fuzz::FuzzScene(data, size); }
