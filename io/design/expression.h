#pragma once
// Expressions of design files: `"=height * 0.6"`, evaluated over the design's
// named parameters (docs/design-files.md, "Parameters and expressions").
// Private to io/design; the expression library stays in expression.cpp.

#include <memory>
#include <string>
#include <vector>

namespace fabmesh {

/// The functions an expression may call, in the order the reference lists them.
const std::vector<std::string>& expression_functions();

/// Whether `name` is a name of the expression library's own (a function or a
/// constant, allowed or not: `pi`, `sin`, `ln`, `_e`, ...): no parameter may take it.
bool is_expression_builtin(const std::string& name);

/// Whether `name` is an identifier: [A-Za-z_][A-Za-z0-9_]*.
bool is_identifier(const std::string& name);

/// Evaluates expressions (the text after the `=`) over named values, in
/// double precision. One per design being read: it holds no state shared
/// with any other, so designs are read on many threads at once.
/// Every error is an InputError whose message says what is wrong with the
/// expression, without its place (the caller knows the place).
class ExpressionEvaluator {
 public:
  ExpressionEvaluator();
  ExpressionEvaluator(const ExpressionEvaluator&) = delete;
  ExpressionEvaluator& operator=(const ExpressionEvaluator&) = delete;
  ~ExpressionEvaluator();

  /// The names `text` uses, other than functions and `pi`, each once, in
  /// order of first use. \throw InputError for a character, an operator, a
  /// function or a constant that expressions do not allow, or an empty text
  std::vector<std::string> names(const std::string& text) const;

  /// Gives `name` the value `value` for the expressions evaluated after.
  void define(const std::string& name, double value);

  /// The value of `text`; every name it uses must be defined. \throw
  /// InputError for a syntax error, a division by zero, the square root of
  /// a negative number, a non-finite result (of any step) or a result above
  /// kMaxDesignNumber in magnitude (io/design/number_limits.h)
  double evaluate(const std::string& text);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fabmesh
