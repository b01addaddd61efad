#include "renderer/passes/pass_graph.h"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

namespace deepgi {

namespace {

[[noreturn]] void fail(const std::string& what) { throw std::runtime_error("pipeline: " + what); }

bool overlap(Levels a, Levels b) { return a == Levels::All || b == Levels::All || a == b; }

bool sameDecl(const TextureDecl& a, const TextureDecl& b) {
    return a.name == b.name && a.layerNames == b.layerNames && a.format == b.format && a.target == b.target &&
           a.size == b.size && a.levels == b.levels;
}

struct Use {
    size_t pass;
    const Channel* channel;
};

}  // namespace

std::vector<TextureDecl> allocations(const std::vector<PassInfo>& passes) {
    std::vector<TextureDecl> out;
    std::map<std::string, std::string> owner;
    for (const auto& p : passes)
        for (const auto& c : p.table.channels()) {
            if (!c.decl) continue;
            auto it = std::find_if(out.begin(), out.end(), [&](const TextureDecl& d) { return d.name == c.texture; });
            if (it == out.end()) {
                out.push_back(*c.decl);
                owner[c.texture] = p.name;
            } else if (c.access != Access::Scratch || it->group != MemoryGroup::Scratch || !sameDecl(*it, *c.decl)) {
                fail("passes '" + owner[c.texture] + "' and '" + p.name + "' both declare texture '" + c.texture +
                     "' (only identical scratch declarations may be shared)");
            }
        }
    return out;
}

std::vector<size_t> schedulePasses(const std::vector<PassInfo>& passes) {
    const size_t n = passes.size();
    std::map<std::string, size_t> byName;
    for (size_t i = 0; i < n; ++i) byName[passes[i].name] = i;
    std::map<std::string, std::vector<Use>> uses;  // texture -> enabled passes' channels
    for (size_t i = 0; i < n; ++i) {
        if (!passes[i].enabled) continue;
        std::map<std::string, std::vector<Access>> seen;
        for (const auto& c : passes[i].table.channels()) {
            auto& acc = seen[c.texture];
            for (Access a : acc)
                if (!(a == Access::History) == !(c.access == Access::History))
                    fail("pass '" + passes[i].name + "' lists texture '" + c.texture + "' twice (" + accessName(a) + ", " +
                         accessName(c.access) + "); only last frame's content and this frame's write may both appear");
            acc.push_back(c.access);
            uses[c.texture].push_back({i, &c});
        }
    }

    std::vector<std::set<size_t>> after(n);  // after[b] = passes that must run before b
    auto edge = [&](size_t from, size_t to) { if (from != to) after[to].insert(from); };
    for (const auto& [tex, list] : uses) {
        std::vector<Use> writes, updates, reads, history, scratch;
        for (const Use& u : list) {
            switch (u.channel->access) {
            case Access::Write: writes.push_back(u); break;
            case Access::Update: updates.push_back(u); break;
            case Access::Read: reads.push_back(u); break;
            case Access::History: history.push_back(u); break;
            case Access::Scratch: scratch.push_back(u); break;
            }
        }
        const std::string& name = tex;
        auto pn = [&](const Use& u) { return "'" + passes[u.pass].name + "'"; };
        if (!scratch.empty()) {
            for (const auto& group : {writes, updates, reads, history})
                if (!group.empty())
                    fail("pass " + pn(group[0]) + " " + accessName(group[0].channel->access) + " '" + name +
                         "', which is scratch of pass " + pn(scratch[0]) + " (scratch content does not outlive a pass)");
            continue;
        }
        if (writes.size() > 1)
            fail("passes " + pn(writes[0]) + " and " + pn(writes[1]) + " both write '" + name +
                 "' in one frame; one of them must declare it an update (read-write), ordered with after()");
        if (!updates.empty() && writes.empty())
            fail("pass " + pn(updates[0]) + " updates '" + name + "', which no pass of this pipeline writes");
        for (const Use& u : updates) {
            for (const Use& w : writes) edge(w.pass, u.pass);
            const std::string& a = u.channel->afterPass;
            if (a.empty()) continue;
            auto it = byName.find(a);
            if (it == byName.end()) fail("pass " + pn(u) + " orders its update of '" + name + "' after '" + a + "', which is not a pass");
            if (!passes[it->second].enabled) continue;  // that pass does not run in this pipeline
            auto other = std::find_if(updates.begin(), updates.end(), [&](const Use& x) { return x.pass == it->second; });
            if (other == updates.end())
                fail("pass " + pn(u) + " orders its update of '" + name + "' after '" + a + "', which does not update it");
            edge(it->second, u.pass);
        }
        // Updates of overlapping levels need an order (a chain of after()).
        for (size_t i = 0; i < updates.size(); ++i)
            for (size_t j = i + 1; j < updates.size(); ++j) {
                if (!overlap(updates[i].channel->levels, updates[j].channel->levels)) continue;
                const size_t a = updates[i].pass, b = updates[j].pass;
                auto reaches = [&](size_t from, size_t to) {  // `to` runs after `from` through the edges so far
                    std::vector<size_t> stack{to};
                    std::set<size_t> seen;
                    while (!stack.empty()) {
                        size_t x = stack.back();
                        stack.pop_back();
                        if (x == from) return true;
                        for (size_t y : after[x]) if (seen.insert(y).second) stack.push_back(y);
                    }
                    return false;
                };
                if (!reaches(a, b) && !reaches(b, a))
                    fail("passes " + pn(updates[i]) + " and " + pn(updates[j]) + " both update '" + name +
                         "' in one frame without an order; declare after() on one of them");
            }
        for (const Use& r : reads) {
            const bool written = std::any_of(writes.begin(), writes.end(), [&](const Use& w) { return overlap(w.channel->levels, r.channel->levels); }) ||
                                 std::any_of(updates.begin(), updates.end(), [&](const Use& w) { return overlap(w.channel->levels, r.channel->levels); });
            if (!written && !r.channel->isOptional)
                fail("pass " + pn(r) + " reads '" + name + "', which no earlier pass writes (no pass of this pipeline writes it)");
            for (const Use& w : writes) if (overlap(w.channel->levels, r.channel->levels)) edge(w.pass, r.pass);
            for (const Use& w : updates) if (overlap(w.channel->levels, r.channel->levels)) edge(w.pass, r.pass);
        }
        for (const Use& h : history) {
            if (writes.empty() && updates.empty() && !h.channel->isOptional)
                fail("pass " + pn(h) + " reads last frame's '" + name + "', which no pass of this pipeline writes");
            for (const Use& w : writes) edge(h.pass, w.pass);
            for (const Use& w : updates) edge(h.pass, w.pass);
        }
    }

    // Kahn's algorithm; among the ready passes the first in the given order runs first.
    std::vector<size_t> order;
    std::vector<bool> done(n, false);
    size_t enabled = 0;
    for (size_t i = 0; i < n; ++i) enabled += passes[i].enabled;
    while (order.size() < enabled) {
        size_t next = n;
        for (size_t i = 0; i < n && next == n; ++i) {
            if (!passes[i].enabled || done[i]) continue;
            if (std::all_of(after[i].begin(), after[i].end(), [&](size_t j) { return done[j]; })) next = i;
        }
        if (next == n) {
            std::string cycle;
            for (size_t i = 0; i < n; ++i)
                if (passes[i].enabled && !done[i]) cycle += (cycle.empty() ? "'" : ", '") + passes[i].name + "'";
            fail("the tables of passes " + cycle + " order them in a cycle (each reads what another writes later)");
        }
        done[next] = true;
        order.push_back(next);
    }
    return order;
}

}  // namespace deepgi
