#include <cstdio>
#include "scene/scene.h"
#include "sim/boundary.h"
#include "sim/fluid.h"
using namespace ranryu;
int main(int argc, char** argv) {
  auto s = scene::load(argv[1]);
  int layers = sim::boundary_layers(s.spacing, sim::kernel_support(s.spacing));
  auto b = sim::sample_boundary(s, layers);
  FILE* f = std::fopen(argv[2], "wb"); std::fwrite(b.data(), sizeof(glm::vec4), b.size(), f); std::fclose(f);
  std::printf("%zu boundary particles, %d layers, spacing %g\n", b.size(), layers, s.spacing);
}
