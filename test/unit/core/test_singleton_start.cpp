// core::chooseQuickSingletonStart (issue 46: start-up of small scenes): Open MPI's quick
// singleton settings are chosen only for a process no launcher started, and never over the
// user's own. (The harness itself called it before MPI_Init; each case sets the environment
// it needs first.)
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <string>

#include "tribos/core/SingletonStart.hpp"

namespace {
const char* const kLaunchers[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"};

void clearAll() {
  for (const char* name : kLaunchers) unsetenv(name);
  unsetenv("OMPI_MCA_ess_singleton_isolated");
  unsetenv("OMPI_MCA_orte_jobfam_session_dir");
  unsetenv("OMPI_MCA_pml");
}
std::string value(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "(unset)";
}
}  // namespace

TEST(SingletonStart, aProcessWithoutLauncherGetsTheIsolatedObOneStart) {
  clearAll();
  EXPECT_TRUE(tribos::core::chooseQuickSingletonStart());
  EXPECT_EQ(value("OMPI_MCA_ess_singleton_isolated"), "1");
  EXPECT_EQ(value("OMPI_MCA_pml"), "ob1");
  // A session directory of its own: isolated singletons would share one.
  EXPECT_NE(value("OMPI_MCA_orte_jobfam_session_dir").find("." + std::to_string(getpid())), std::string::npos);
  EXPECT_FALSE(tribos::core::chooseQuickSingletonStart());  // already chosen: nothing changes
}

TEST(SingletonStart, aLaunchedProcessKeepsTheSitesChoice) {
  for (const char* launcher : kLaunchers) {
    SCOPED_TRACE(launcher);
    clearAll();
    setenv(launcher, "0", 1);
    EXPECT_FALSE(tribos::core::chooseQuickSingletonStart());
    EXPECT_EQ(value("OMPI_MCA_pml"), "(unset)");
    EXPECT_EQ(value("OMPI_MCA_ess_singleton_isolated"), "(unset)");
    EXPECT_EQ(value("OMPI_MCA_orte_jobfam_session_dir"), "(unset)");
  }
}

TEST(SingletonStart, theUsersOwnLayerStays) {
  clearAll();
  setenv("OMPI_MCA_pml", "ucx", 1);
  EXPECT_TRUE(tribos::core::chooseQuickSingletonStart());
  EXPECT_EQ(value("OMPI_MCA_pml"), "ucx");
  EXPECT_EQ(value("OMPI_MCA_ess_singleton_isolated"), "1");
}
