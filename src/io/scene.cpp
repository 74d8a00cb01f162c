#include "roller/io/scene.hpp"

namespace roller {

int Scene::total_steps() const { return steps.n_steps * passes.count; }

}  // namespace roller
