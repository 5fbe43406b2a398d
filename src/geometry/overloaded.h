#pragma once
// The visitor idiom for std::visit over several lambdas.

namespace fastron {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// Clang 14 does not deduce aggregate template arguments by itself (C++20's P1816).
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace fastron
