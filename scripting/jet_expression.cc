// The evaluator of a JetExpression: runs its postfix program on (value,
// rate, acceleration) triples (scripting/jet_expression.h).
#include "scripting/jet_expression.h"

#include <cmath>
#include <string>

#include "mech/errors.h"
#include "scripting/jet_rules.h"

namespace mechflow::scripting {

using mech::Jet;
using namespace jet;

template <bool kFindFailure>
Jet JetExpression::RunProgram(const Instruction* code, int size, double t, int* failed) {
  Triple stack[kMaxStackDepth + 1];  // stack[0] is never used, so top[-1] is always in the array
  Triple* top = stack + 1;           // one past the top
  for (int i = 0; i < size; ++i) {
    const Instruction& in = code[i];
    Triple& x = top[-1];  // the operand of one-operand instructions
    switch (in.op) {
      case Op::kConst:
        *top++ = {in.c, 0, 0};
        break;
      case Op::kTime:
        *top++ = {t, 1, 0};
        break;
      case Op::kNeg:
        x = {-x.v, -x.d, -x.dd};
        break;
      case Op::kAdd:
        --top;
        top[-1] = {top[-1].v + top[0].v, top[-1].d + top[0].d, top[-1].dd + top[0].dd};
        break;
      case Op::kSub:
        --top;
        top[-1] = {top[-1].v - top[0].v, top[-1].d - top[0].d, top[-1].dd - top[0].dd};
        break;
      case Op::kMul:
        --top;
        top[-1] = Multiply(top[-1], top[0]);
        break;
      case Op::kDiv:
        --top;
        top[-1] = Divide(top[-1], top[0]);
        break;
      case Op::kPow:
        --top;
        top[-1] = Power(top[-1], top[0]);
        break;
      case Op::kMin:
        --top;
        top[-1] = Min(top[-1], top[0]);
        break;
      case Op::kMax:
        --top;
        top[-1] = Max(top[-1], top[0]);
        break;
      case Op::kAtan2:
        --top;
        top[-1] = Atan2(top[-1], top[0]);
        break;
      case Op::kAddC:
        x.v += in.c;
        break;
      case Op::kSubC:
        x.v -= in.c;
        break;
      case Op::kRSubC:
        x = {in.c - x.v, -x.d, -x.dd};
        break;
      case Op::kMulC:
        x = {x.v * in.c, x.d * in.c, x.dd * in.c};
        break;
      case Op::kDivC:
        x = {x.v / in.c, x.d / in.c, x.dd / in.c};
        break;
      case Op::kRDivC:
        x = DivideInto(in.c, x);
        break;
      case Op::kPowC:
        x = PowerOfConstant(x, in.c);
        break;
      case Op::kRPowC:
        x = ConstantToPower(in.c, x);
        break;
      case Op::kSin: {
        const double s = std::sin(x.v), c = std::cos(x.v);
        x = Chain(x, s, c, -s);
        break;
      }
      case Op::kCos: {
        const double s = std::sin(x.v), c = std::cos(x.v);
        x = Chain(x, c, -s, -c);
        break;
      }
      case Op::kTan: {
        const double tn = std::tan(x.v), sec2 = 1 + tn * tn;
        x = Chain(x, tn, sec2, 2 * tn * sec2);
        break;
      }
      case Op::kAsin: {
        const double r = 1 / std::sqrt(1 - x.v * x.v);
        x = Chain(x, std::asin(x.v), r, x.v * r * r * r);
        break;
      }
      case Op::kAcos: {
        const double r = 1 / std::sqrt(1 - x.v * x.v);
        x = Chain(x, std::acos(x.v), -r, -x.v * r * r * r);
        break;
      }
      case Op::kAtan: {
        const double r = 1 / (1 + x.v * x.v);
        x = Chain(x, std::atan(x.v), r, -2 * x.v * r * r);
        break;
      }
      case Op::kSinh: {
        const double sh = std::sinh(x.v), ch = std::cosh(x.v);
        x = Chain(x, sh, ch, sh);
        break;
      }
      case Op::kCosh: {
        const double sh = std::sinh(x.v), ch = std::cosh(x.v);
        x = Chain(x, ch, sh, ch);
        break;
      }
      case Op::kTanh: {
        const double th = std::tanh(x.v), sech2 = 1 - th * th;
        x = Chain(x, th, sech2, -2 * th * sech2);
        break;
      }
      case Op::kExp: {
        const double e = std::exp(x.v);
        x = Chain(x, e, e, e);
        break;
      }
      case Op::kLn:
        x = Chain(x, std::log(x.v), 1 / x.v, -1 / (x.v * x.v));
        break;
      case Op::kSqrt: {
        const double s = std::sqrt(x.v);
        x = Chain(x, s, 0.5 / s, -0.25 / (s * x.v));
        break;
      }
      case Op::kSqr:
        x = Chain(x, x.v * x.v, 2 * x.v, 2);
        break;
      case Op::kAbs:
        x = Abs(x);
        break;
      case Op::kSign:
        x = Sign(x);
        break;
    }
    if constexpr (kFindFailure) {
      if (!IsFinite(top[-1])) {
        *failed = i;
        return {top[-1].v, top[-1].d, top[-1].dd};
      }
    }
  }
  if constexpr (kFindFailure) *failed = -1;
  return {stack[1].v, stack[1].d, stack[1].dd};
}

Jet JetExpression::Evaluate(double t) const {
  // a constant (folded at compilation): its value, without running the program
  if (program_.size() == 1 && program_[0].op == Op::kConst && std::isfinite(program_[0].c))
    return {program_[0].c, 0.0, 0.0};
  const Jet result = RunProgram<false>(program_.data(), static_cast<int>(program_.size()), t, nullptr);
  if (!(std::isfinite(result.value) && std::isfinite(result.rate) && std::isfinite(result.acceleration)))
    ThrowNotFinite(t, result);
  return result;
}

void JetExpression::ThrowNotFinite(double t, const Jet& result) const {
  // run again, stopping at the first part that is not finite
  const int size = static_cast<int>(program_.size());
  int failed = -1;
  Jet part = RunProgram<true>(program_.data(), size, t, &failed);
  std::string where;
  if (failed >= 0 && failed + 1 < size) {
    const auto [begin, end] = spans_[failed];
    where = ": its part '" + text_.substr(begin, end - begin) + "' is not";
  } else {
    part = result;
  }
  throw SimulationError(what_ + ": time function '" + text_ + "' is not finite at t = " + Number(t) + where +
                        " (value " + Number(part.value) + ", rate " + Number(part.rate) + ", acceleration " +
                        Number(part.acceleration) + ")");
}

// the compiler folds constants with both forms
template Jet JetExpression::RunProgram<false>(const Instruction*, int, double, int*);
template Jet JetExpression::RunProgram<true>(const Instruction*, int, double, int*);

}  // namespace mechflow::scripting
