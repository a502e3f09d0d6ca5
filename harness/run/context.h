/// Facts about the machine a run or benchmark ran on (the report's context block is
/// ContextFacts, harness/run/runner.h; benchmarks print the same facts).
#pragma once
#include <string>

namespace aalab {

/// The CPU's model name from /proc/cpuinfo ("unknown" where it is not there).
std::string CpuModel();

}  // namespace aalab
