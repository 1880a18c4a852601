#include "io/design/yaml/node_budget.h"

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include <cstdint>
#include <sstream>
#include <vector>

#include "geometry/core/errors.h"

namespace fabmesh::yaml {
namespace {

// Counts nodes as the parser reports them; an anchored node remembers its
// size so that each alias of it adds that size.
class NodeCounter : public YAML::EventHandler {
 public:
  NodeCounter(const std::string& path, std::size_t max_nodes, const std::string& override_text)
      : path_(path), max_nodes_(max_nodes), override_text_(override_text) {}

  void OnDocumentStart(const YAML::Mark& /*mark*/) override { anchor_sizes_.clear(); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override { leaf(mark, anchor); }
  void OnScalar(const YAML::Mark& mark, const std::string& /*tag*/, YAML::anchor_t anchor,
                const std::string& /*value*/) override {
    leaf(mark, anchor);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    const std::uint64_t size = anchor < anchor_sizes_.size() ? anchor_sizes_[anchor] : 0;
    if (size == 0) {
      // Known to the parser but not complete: the alias is inside the node it names.
      fail(mark, "an alias may not stand for a node that contains it");
    }
    add(mark, size);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string& /*tag*/, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value /*style*/) override {
    open(mark, anchor);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string& /*tag*/, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value /*style*/) override {
    open(mark, anchor);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Open {
    YAML::anchor_t anchor;
    std::uint64_t count_at_start;
  };

  [[noreturn]] void fail(const YAML::Mark& mark, const std::string& message) const {
    if (!override_text_.empty())
      throw FileError(path_, 0, 0, fmt::format("-D {}: {}", override_text_, message));
    if (mark.line < 0) throw FileError(path_, 0, 0, fmt::format("{}: {}", path_, message));
    throw FileError(path_, mark.line + 1, mark.column + 1,
                    fmt::format("{}:{}:{}: {}", path_, mark.line + 1, mark.column + 1, message));
  }

  void add(const YAML::Mark& mark, std::uint64_t nodes) {
    count_ += nodes;  // nodes <= max_nodes_ and count_ <= max_nodes_ before: no overflow
    if (count_ > max_nodes_) {
      fail(mark, fmt::format("the {} holds more than {} YAML values (scalars, lists and maps, each alias "
                             "counted as what it stands for); long point lists belong in a CSV file: "
                             "`polyline: {{file: points.csv}}`",
                             override_text_.empty() ? "design" : "value", max_nodes_));
    }
  }

  void remember(YAML::anchor_t anchor, std::uint64_t size) {
    if (anchor == YAML::NullAnchor) return;
    if (anchor >= anchor_sizes_.size()) anchor_sizes_.resize(anchor + 1, 0);
    anchor_sizes_[anchor] = size;
  }

  void leaf(const YAML::Mark& mark, YAML::anchor_t anchor) {
    add(mark, 1);
    remember(anchor, 1);
  }

  void open(const YAML::Mark& mark, YAML::anchor_t anchor) {
    add(mark, 1);
    if (stack_.size() >= kMaxYamlDepth) {
      fail(mark,
           fmt::format("lists and maps nested more than {} deep here: a design needs a handful of levels",
                       kMaxYamlDepth));
    }
    if (anchor != YAML::NullAnchor && anchor >= anchor_sizes_.size()) anchor_sizes_.resize(anchor + 1, 0);
    stack_.push_back({anchor, count_ - 1});
  }

  void close() {
    if (stack_.empty()) return;
    const Open o = stack_.back();
    stack_.pop_back();
    remember(o.anchor, count_ - o.count_at_start);
  }

  const std::string& path_;
  std::size_t max_nodes_;
  const std::string& override_text_;
  std::uint64_t count_ = 0;
  std::vector<Open> stack_;
  std::vector<std::uint64_t> anchor_sizes_;  // by anchor id; 0 while the anchored node is open
};

}  // namespace

void require_node_budget(const std::string& text, const std::string& path, std::size_t max_nodes,
                         const std::string& override_text) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  NodeCounter counter(path, max_nodes, override_text);
  while (parser.HandleNextDocument(counter)) {
  }
}

}  // namespace fabmesh::yaml
