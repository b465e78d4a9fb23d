#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rigid/common/error.hpp"

/// Expects `statement` to throw rigid::Error whose message contains `substring`.
#define EXPECT_RIGID_ERROR(statement, substring)                                        \
  EXPECT_THAT([&]() { statement; },                                                     \
              ::testing::ThrowsMessage<::rigid::Error>(::testing::HasSubstr(substring)))
