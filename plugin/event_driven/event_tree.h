// The event queue: a complete binary tournament tree over the disks (Isobe, Int. J. Mod. Phys.
// C 10, 1281 (1999); Marin et al., J. Comput. Phys. 109, 306 (1993)). Each disk has one entry,
// the time of its next predicted event; every internal node holds the disk with the earliest
// time below it, so the next event is at the root and changing one disk's time costs one pass
// up the tree, O(log N).
#ifndef MN_EVENT_DRIVEN_EVENT_TREE_H
#define MN_EVENT_DRIVEN_EVENT_TREE_H

#include <limits>
#include <vector>

namespace mn {
namespace ed {

class EventTree {
 public:
  explicit EventTree(int n)
  {
    leaves_ = 1;
    while (leaves_ < n) leaves_ *= 2;
    time_.assign(leaves_, std::numeric_limits<double>::infinity());
    node_.assign(2 * leaves_, 0);
    for (int k = 0; k < leaves_; k++) node_[leaves_ + k] = k;
    for (int k = leaves_ - 1; k >= 1; k--) node_[k] = earlier(node_[2 * k], node_[2 * k + 1]);
  }

  // The disk with the earliest event (ties: the lower index) and that time.
  int first() const { return node_[1]; }
  double first_time() const { return time_[node_[1]]; }
  double time(int disk) const { return time_[disk]; }

  void set(int disk, double t)
  {
    time_[disk] = t;
    for (int k = (leaves_ + disk) / 2; k >= 1; k /= 2) {
      const int best = earlier(node_[2 * k], node_[2 * k + 1]);
      if (node_[k] == best && best != disk) break;    // nothing above changes
      node_[k] = best;
    }
  }

 private:
  int earlier(int a, int b) const
  {
    return time_[b] < time_[a] || (time_[b] == time_[a] && b < a) ? b : a;
  }

  int leaves_;
  std::vector<double> time_;    // per leaf (padding leaves: infinity)
  std::vector<int> node_;       // 1-based heap layout; node_[leaves_ + k] = k
};

}    // namespace ed
}    // namespace mn

#endif
