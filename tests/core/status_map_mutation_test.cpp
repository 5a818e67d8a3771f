// The compile-time check behind the status maps (detail/status_map.hpp): names_agree looks at every
// enumerator from First to Last, the last one included, and says false when any outcome's name differs.
#include <gtest/gtest.h>

#include "trionet/detail/status_map.hpp"

namespace names_agree_test {

enum class step : unsigned char { begun, going, done };
enum class outcome : unsigned char { nothing, begun, going, done };
enum class wrong_at_the_end : unsigned char { nothing, begun, going, finished };

constexpr const char* to_string(step s) noexcept {
  return s == step::begun ? "begun" : s == step::going ? "going" : "done";
}
constexpr const char* to_string(outcome o) noexcept {
  return o == outcome::nothing ? "nothing"
         : o == outcome::begun ? "begun"
         : o == outcome::going ? "going"
                               : "done";
}
constexpr const char* to_string(wrong_at_the_end w) noexcept {
  return w == wrong_at_the_end::nothing ? "nothing"
         : w == wrong_at_the_end::begun ? "begun"
         : w == wrong_at_the_end::going ? "going"
                                        : "finished";
}

static_assert(trionet::detail::names_agree<step::begun, step::done, outcome::begun>(), "all three agree");
static_assert(!trionet::detail::names_agree<step::begun, step::done, wrong_at_the_end::begun>(),
              "the last enumerator is checked too");
static_assert(!trionet::detail::names_agree<step::begun, step::done, outcome::nothing>(), "shifted by one");

}  // namespace names_agree_test

TEST(StatusMap, NamesAgreeChecksEveryEnumeratorTheLastIncluded) {
  EXPECT_EQ((trionet::detail::status_map<names_agree_test::step::begun, names_agree_test::step::done,
                                         names_agree_test::outcome::begun>::of(names_agree_test::step::done)),
            names_agree_test::outcome::done);
}
