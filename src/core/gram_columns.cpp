#include "gram_columns.h"

namespace fastron::detail {

const GramPasses& activeGramPasses() {
#ifdef FASTRON_SIMD_DISPATCH
  switch (activeSimdPath()) {
    case SimdPath::Avx2:
      return avx2::kGramPasses;
    case SimdPath::Avx512:
      return avx512::kGramPasses;
    case SimdPath::Portable:
      break;
  }
#endif
  return portable::kGramPasses;
}

}  // namespace fastron::detail
