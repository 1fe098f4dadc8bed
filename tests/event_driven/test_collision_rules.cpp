#include "mn_collision.h"
#include <gtest/gtest.h>
TEST(Placeholder, Builds) { SUCCEED(); }
