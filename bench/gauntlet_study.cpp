// The solver design study (docs/solver.md): every gauntlet case (tests/gauntlet.h) under each
// solver setting given, one line per case and setting with its measures and cost.
//
//   build/bench/gauntlet_study [K:n ...]      e.g. 2:1 4:1 1:8     (default: a fixed list)
#include "../tests/gauntlet.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

using namespace tandem::gauntlet;

int main(int argc, char** argv) {
  std::vector<Override> settings;
  for (int a = 1; a < argc; ++a) {
    Override o;
    if (std::sscanf(argv[a], "%d:%d", &o.iterations, &o.substeps) != 2 || o.iterations < 1 || o.substeps < 1) {
      std::fprintf(stderr, "gauntlet_study: '%s' is not K:n (iterations:substeps)\n", argv[a]);
      return 2;
    }
    settings.push_back(o);
  }
  if (settings.empty()) settings = {{2, 1}, {4, 1}, {1, 4}, {1, 8}, {2, 4}};
  const std::vector<std::pair<const char*, std::function<Outcome(const Override&)>>> cases = {
      {"atwood", [](const Override& o) { return atwood(o); }},
      {"capstan hold", [](const Override& o) { return capstan(true, o); }},
      {"capstan slide", [](const Override& o) { return capstan(false, o); }},
      {"heavy pendulum", [](const Override& o) { return heavyPendulum(o); }},
      {"long rope", [](const Override& o) { return longRope(o); }},
      {"free swing", [](const Override& o) { return freeSwing(o); }},
      {"cloth 51", [](const Override& o) { return clothOnSphere("cloth_sphere.json", 3.0, o); }},
      {"cloth 101", [](const Override& o) { return clothOnSphere("gauntlet/cloth_sphere_101.json", 2.0, o); }},
      {"cloth 201", [](const Override& o) { return clothOnSphere("gauntlet/cloth_sphere_201.json", 1.5, o); }},
      {"projectile 20", [](const Override& o) { return projectile(20, o); }},
      {"projectile 60", [](const Override& o) { return projectile(60, o); }},
      {"projectile drop", [](const Override& o) { return projectile(20, o, 0.5); }},
      {"rope wheel", [](const Override& o) { return ropeWheel(o); }},
      {"hammock", [](const Override& o) { return restOnCloth("hammock.json", "hammock", o); }},
      {"box stack", [](const Override& o) { return restOnCloth("gauntlet/box_stack_on_cloth.json", "hammock", o); }},
  };
  const char* only = std::getenv("GAUNTLET_ONLY");  // a case name's prefix
  for (const auto& [name, run] : cases) {
    if (only && std::strncmp(name, only, std::strlen(only)) != 0) continue;
    for (const Override& o : settings) {
      const Outcome r = run(o);
      std::printf("%-15s K=%-2d n=%-2d %-4s %8.2f ms ", name, o.iterations, o.substeps, r.pass() ? "pass" : "FAIL",
                  r.msPerStep);
      if (!r.error.empty()) std::printf(" error: %.120s", r.error.c_str());
      for (const Measure& m : r.measures) std::printf(" | %s %.4g%s", m.name.c_str(), m.value, m.pass() ? "" : " (!)");
      std::printf("\n");
      std::fflush(stdout);
    }
  }
}
