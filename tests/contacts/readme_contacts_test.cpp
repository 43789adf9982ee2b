// Runs the README's contacts example (cut out of README.md by tests/CMakeLists.txt): it
// returns 0 when the box rests with its contacts carrying its weight.
#include <gtest/gtest.h>

int contacts_example();

TEST(ReadmeContacts, ExampleRunsAndTheContactsCarryTheWeight) {
  EXPECT_EQ(contacts_example(), 0);
}
