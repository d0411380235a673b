#include "core/shared_cache.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace oitbench {
namespace {

TEST(SharedCache, BuildsOncePerKeyAndTypeAndKeepsTheMostRecent) {
  SharedCache cache(2);
  int built = 0;
  auto make = [&](int v) {
    return std::function<std::shared_ptr<const int>()>([&built, v] {
      ++built;
      return std::make_shared<const int>(v);
    });
  };
  auto a = cache.get<int>("a", make(1));
  EXPECT_EQ(*cache.get<int>("a", make(99)), 1);  // the stored one, not rebuilt
  EXPECT_EQ(built, 1);
  EXPECT_EQ(a.get(), cache.get<int>("a", make(99)).get());
  // The same key for another type is another entry.
  EXPECT_EQ(*cache.get<std::string>("a", [] { return std::make_shared<const std::string>("s"); }), "s");
  EXPECT_EQ(cache.misses(), 2u);
  // Capacity 2 per type: the string does not count against the ints; "b" makes two ints, "c" a third,
  // which evicts the least recently used, "a", so it is built again.
  cache.get<int>("b", make(2));
  EXPECT_EQ(*cache.get<int>("a", make(98)), 1);
  cache.get<int>("c", make(4));
  EXPECT_EQ(*cache.get<int>("b", make(3)), 3);
  EXPECT_EQ(built, 4);
  EXPECT_EQ(*cache.get<std::string>("a", [] { return std::make_shared<const std::string>("t"); }), "s");
  EXPECT_EQ(*a, 1);  // what a case holds outlives its eviction
}

TEST(SharedCache, ATypeMayKeepMoreThanTheCapacity) {
  SharedCache cache(1);
  for (int i = 0; i < 5; ++i)
    cache.get<int>(
        std::to_string(i), [i] { return std::make_shared<const int>(i); }, 5);
  for (int i = 0; i < 5; ++i)
    EXPECT_EQ(*cache.get<int>(
                  std::to_string(i), [] { return std::make_shared<const int>(-1); }, 5),
              i);
  EXPECT_EQ(cache.misses(), 5u);
}

TEST(SharedCache, AFailedBuildStoresNothingAndCapacityZeroSharesNothing) {
  SharedCache cache(2);
  EXPECT_THROW(cache.get<int>("k", []() -> std::shared_ptr<const int> { throw std::runtime_error("no"); }),
               std::runtime_error);
  EXPECT_EQ(*cache.get<int>("k", [] { return std::make_shared<const int>(7); }), 7);
  SharedCache none(0);
  auto x = none.get<int>("k", [] { return std::make_shared<const int>(1); });
  auto y = none.get<int>("k", [] { return std::make_shared<const int>(2); });
  EXPECT_NE(*x, *y);
}

}  // namespace
}  // namespace oitbench
