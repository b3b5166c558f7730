// core/progress.h: what it writes to a log (one line per 10%), to a terminal (one redrawn line), and
// that it can be silenced; the number and time formats.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/progress.h"

namespace {

using bounce::core::Progress;

std::string contents(std::FILE* f)
{
    std::fflush(f);
    std::rewind(f);
    std::string s;
    char buf[512];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) s.append(buf, n);
    return s;
}

int count(const std::string& s, const std::string& what)
{
    int c = 0;
    for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++c;
    return c;
}

TEST(Progress, LogGetsOneLinePerTenPercentAndATotal)
{
    std::FILE* f = std::tmpfile();
    ASSERT_NE(f, nullptr);
    {
        Progress p("render", 200.0, "samples", {f, 0, true});
        for (int i = 0; i < 200; ++i) p.add(1.0);
    } // the destructor writes the last line
    const std::string s = contents(f);
    std::fclose(f);
    EXPECT_EQ(count(s, "\n"), 10) << s; // 10% ... 90%, then "done"
    EXPECT_NE(s.find("render: 10%"), std::string::npos) << s;
    EXPECT_NE(s.find("render: 90%"), std::string::npos) << s;
    EXPECT_NE(s.find("render: done, 200 samples"), std::string::npos) << s;
    EXPECT_EQ(s.find('\r'), std::string::npos);
}

TEST(Progress, TerminalGetsARedrawnBar)
{
    std::FILE* f = std::tmpfile();
    ASSERT_NE(f, nullptr);
    {
        Progress p("bake", 10.0, "items", {f, 1, true});
        p.setNote("noise 1.0%");
        p.set(5.0);
        std::this_thread::sleep_for(std::chrono::milliseconds(120));
        p.set(6.0);
        p.finish();
        p.finish(); // once only
    }
    const std::string s = contents(f);
    std::fclose(f);
    EXPECT_NE(s.find('\r'), std::string::npos);
    EXPECT_NE(s.find("ETA"), std::string::npos) << s;
    EXPECT_NE(s.find("60%"), std::string::npos) << s;
    EXPECT_NE(s.find("noise 1.0%"), std::string::npos) << s;
    EXPECT_EQ(count(s, "done"), 1) << s;
}

TEST(Progress, SilentWhenDisabledOrByEnvironment)
{
    std::FILE* f = std::tmpfile();
    ASSERT_NE(f, nullptr);
    {
        Progress p("x", 10.0, "u", {f, 0, false});
        p.add(10.0);
    }
    setenv("BOUNCE_PROGRESS", "0", 1);
    {
        Progress p("y", 10.0, "u", {f, 1, true});
        p.add(10.0);
    }
    unsetenv("BOUNCE_PROGRESS");
    EXPECT_EQ(contents(f), "");
    std::fclose(f);
}

TEST(Progress, ThreadSafeAdds)
{
    std::FILE* f = std::tmpfile();
    ASSERT_NE(f, nullptr);
    Progress p("t", 4000.0, "u", {f, 0, true});
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&p] {
            for (int i = 0; i < 1000; ++i) p.add(1.0);
        });
    for (std::thread& t : threads) t.join();
    EXPECT_EQ(p.done(), 4000.0);
    p.finish();
    std::fclose(f);
}

TEST(Progress, Formats)
{
    EXPECT_EQ(Progress::si(12.0), "12.0");
    EXPECT_EQ(Progress::si(1234.0), "1.23 k");
    EXPECT_EQ(Progress::si(5.6e6), "5.60 M");
    EXPECT_EQ(Progress::si(999.9e6), "1.00 G");
    EXPECT_EQ(Progress::clock(0.42), "0.42 s");
    EXPECT_EQ(Progress::clock(12.34), "12.3 s");
    EXPECT_EQ(Progress::clock(754.0), "12:34");
    EXPECT_EQ(Progress::clock(3723.0), "1:02:03");
    EXPECT_EQ(Progress::clock(-1.0), "?");
}

} // namespace
