#pragma once
// Disjoint sets over 0..n-1 whose representative is always the set's smallest element, so that
// "one element per set" choices (regions, copies of cut nodes, pressures to hold) do not depend
// on the order of the unions.
#include <algorithm>
#include <numeric>
#include <vector>

namespace curvemesh::mesh {

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void unite(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

}  // namespace curvemesh::mesh
