#include "systems/clear_system.h"

namespace fibra {

void clearSystem(const FibreStore& fs, const IterationInput& input, LinearSystem& ls) {
  ls.r.setZero(fs.q.size());
  if (input.withTangent) ls.K.coeffs().setZero();
}

}  // namespace fibra
