#pragma once
// The visitor idiom for std::visit over several lambdas.

namespace fastron {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};

}  // namespace fastron
