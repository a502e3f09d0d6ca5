#include "harness/run/stage_clock.h"

#include <sys/resource.h>

#include <cstdio>

namespace aalab {

double ProcessCpuMs() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  const auto ms = [](const timeval& t) { return static_cast<double>(t.tv_sec) * 1e3 + t.tv_usec / 1e3; };
  return ms(u.ru_utime) + ms(u.ru_stime);
}

StageClock::StageClock(std::vector<std::string> order) : last_cpu_ms_(ProcessCpuMs()) {
  for (auto& s : order) stages_.push_back({std::move(s), 0, 0});
}

void StageClock::Charge() {
  const double wall = wall_.ElapsedMs(), cpu = ProcessCpuMs();
  if (!current_.empty()) {
    StageTime* t = nullptr;
    for (auto& s : stages_) {
      if (s.stage == current_) t = &s;
    }
    if (!t) {
      stages_.push_back({current_, 0, 0});
      t = &stages_.back();
    }
    t->wall_ms += wall - last_wall_ms_;
    t->cpu_ms += cpu - last_cpu_ms_;
  }
  last_wall_ms_ = wall;
  last_cpu_ms_ = cpu;
}

void StageClock::Enter(const std::string& stage) {
  Charge();
  current_ = stage;
}

std::vector<StageTime> StageClock::Finish() {
  Charge();
  current_.clear();
  std::vector<StageTime> out = stages_;
  StageTime total{"total", 0, 0};
  for (const auto& s : stages_) {
    total.wall_ms += s.wall_ms;
    total.cpu_ms += s.cpu_ms;
  }
  out.push_back(total);
  return out;
}

std::string FormatTimeBreakdown(const std::vector<StageTime>& stages) {
  double total = 0;
  for (const auto& s : stages) {
    if (s.stage == "total") total = s.wall_ms;
  }
  std::string out = "time breakdown (wall s, CPU s of all threads, share of wall):\n";
  char line[160];
  for (const auto& s : stages) {
    std::snprintf(line, sizeof line, "  %-24s %8.2f %8.2f %5.1f%%\n", s.stage.c_str(), s.wall_ms / 1e3, s.cpu_ms / 1e3,
                  total > 0 ? 100.0 * s.wall_ms / total : 0.0);
    out += line;
  }
  return out;
}

}  // namespace aalab
