/* The monitor (docs/host-link.md §5.8): protocol frames in full, channel data as counts.
 *
 * Every frame heard or sent that is not channel data goes to a ring of MON_RING frames;
 * channel data frames are counted per channel node ID.  When the link has nothing else to
 * send, FRAMES events carry the ring (with how many frames were dropped since the last one)
 * and, every period, CHANNEL_COUNTS events the counts — within a token bucket of half the
 * line (6,400 bytes/s at 128000 baud).  Built unless MONITOR is 0 (the AVR build leaves it
 * out: capability bit 0 is then not declared and MONITOR answers UNSUPPORTED).
 */
#include <string.h>
#include "arb.h"
#include "port.h"

#if MONITOR
#define MON_RING 16
#define BUDGET 6400u

static struct { uint32_t t; uint16_t id; uint8_t len, data[8]; } ring[MON_RING];
static uint8_t head, count, frames_on, counts_on;
static uint16_t dropped, period_ms;
static uint16_t counts[NODE_ID_MAX + 1];
static uint32_t period_start, tokens_at;
static uint32_t tokens;

uint16_t mon_configure(uint8_t flags, uint8_t period)
{
    frames_on = flags & 1;
    counts_on = (flags >> 1) & 1;
    period_ms = (uint16_t)((period ? period : 1) * 100u);
    period_start = tokens_at = port_millis();
    tokens = BUDGET / 4;
    head = count = 0;
    dropped = 0;
    memset(counts, 0, sizeof counts);
    return BUDGET;
}

void mon_stop(void) { frames_on = counts_on = 0; }

void mon_frame(uint16_t id, const uint8_t *data, uint8_t len)
{
    uint8_t node = (uint8_t)id;
    if (!(id >> 8 & 1) && (id >> 9) != 3 && nodes_is_channel(node)) {
        if (counts_on && counts[node] < 0xFFFF) counts[node]++;
        return;
    }
    if (!frames_on) return;
    if (count == MON_RING) { if (dropped < 0xFFFF) dropped++; return; }
    uint8_t slot = (uint8_t)((head + count) % MON_RING);
    ring[slot].t = port_millis();
    ring[slot].id = id;
    ring[slot].len = len > 8 ? 8 : len;
    memcpy(ring[slot].data, data, ring[slot].len);
    count++;
}

static int spend(uint16_t n)
{
    uint32_t now = port_millis();
    tokens += (now - tokens_at) * BUDGET / 1000u;
    tokens_at = now;
    if (tokens > BUDGET) tokens = BUDGET;
    if (tokens < n) return 0;
    tokens -= n;
    return 1;
}

/* A monitor message to send now into msg (room 255), or 0. */
int mon_take(uint8_t *msg)
{
    uint32_t now = port_millis();
    if (counts_on && now - period_start >= period_ms) {
        int n = 3;
        msg[0] = 0x48;
        put16(msg + 1, (uint16_t)(now - period_start));
        for (int id = NODE_ID_MIN; id <= NODE_ID_MAX && n + 3 <= 255; id++) {
            if (!counts[id]) continue;
            msg[n] = (uint8_t)id; put16(msg + n + 1, counts[id]);
            n += 3;
        }
        if (!spend((uint16_t)n)) return 0;   /* the counts wait (and keep counting) */
        for (int i = 3; i < n; i += 3) counts[msg[i]] = 0;
        period_start = now;
        return n;
    }
    if (frames_on && (count || dropped)) {
        int n = 3;
        msg[0] = 0x47;
        while (count && n + 7 + ring[head].len <= 255) {
            put32(msg + n, ring[head].t); put16(msg + n + 4, ring[head].id);
            msg[n + 6] = ring[head].len;
            memcpy(msg + n + 7, ring[head].data, ring[head].len);
            n += 7 + ring[head].len;
            head = (uint8_t)((head + 1) % MON_RING);
            count--;
        }
        put16(msg + 1, dropped);
        /* frames leave room in the bucket for the next counts (they come first) */
        if (!spend((uint16_t)(n + (counts_on ? 64 : 0)))) {           /* over budget: these frames are dropped */
            uint16_t lost = 0;
            for (int i = 3; i < n; i += 7 + msg[i + 6]) lost++;
            dropped = (uint16_t)(dropped + lost);
            return 0;
        }
        if (counts_on) tokens += 64;
        dropped = 0;
        return n;
    }
    return 0;
}
#endif
