/* The stored-configuration byte format (reference §3), read straight from non-volatile memory.
 *
 * 3-byte records (code u8, value u16 LE).  The reader is as strict as PDCP Studio's
 * (storage/config_codec.py): a count that disagrees with what follows, a value record outside
 * a channel, a channel without index/VID/PID/serial, a link without both channels, a missing
 * End, or a checksum record (code 16, CRC-16/CCITT-FALSE of every byte before it, directly
 * before End) that does not match are refused with the record's offset.  Unknown codes are
 * skipped here; the bytes themselves are stored as received, so they survive.  The links of
 * every configuration go to g_stored (up to MAX_STORED_LINKS) for start-up.
 */
#include <string.h>
#include "arb.h"
#include "port.h"

stored_link_t g_stored[MAX_STORED_LINKS];
uint16_t g_nstored;

typedef struct { uint16_t v[15]; uint16_t seen; } chan_vals_t;

static int fail(char *why, int room, const char *text, uint32_t off)
{
    fmt_text(why, room, "%s (at byte %u)", text, (unsigned)off);
    return -1;
}

static void to_end(const chan_vals_t *c, ch_ref_t *r, uint16_t *type, uint16_t *profile)
{
    r->index = (uint8_t)c->v[9]; r->vid = c->v[10]; r->pid = c->v[11]; r->serial = c->v[12];
    *type = c->v[7]; *profile = c->v[8];
}

int config_decode(int area, uint32_t base, uint32_t len, char *why, int room)
{
    uint8_t buf[48];
    uint32_t have = 0, at = 0;      /* buf holds bytes [at, at + have) of the payload */
    int count = -1, nconfigs = 0, cfg = 0, link_count = -1, links_in_cfg = 0;
    int in_link = 0, chan = 0;      /* chan: 0 none, 5 input, 6 output */
    uint8_t ends = 0;               /* bit 0 input done, bit 1 output done */
    uint32_t count_off = 0, lc_off = 0, link_off = 0, chan_off = 0;
    uint16_t crc = 0xFFFF;
    int checksum_seen = 0;
    chan_vals_t cv, in_v, out_v;
    stored_link_t cur;
    memset(&cv, 0, sizeof cv); memset(&in_v, 0, sizeof in_v); memset(&out_v, 0, sizeof out_v);
    g_nstored = 0;
    if (len % 3 && len < 3) return fail(why, room, "truncated record", 0);
    for (uint32_t off = 0; off + 3 <= len; off += 3) {
        uint8_t rec[3];
        for (int i = 0; i < 3; i++) {
            uint32_t p = off + (uint32_t)i;
            if (p >= at + have) {
                at = p;
                have = len - p < sizeof buf ? len - p : sizeof buf;
                if (area < 0 ? mem_read(p, buf, have) : port_nvm_read(area, base + p, buf, have))
                    return fail(why, room, "memory read failed", p);
            }
            rec[i] = buf[p - at];
        }
        uint8_t code = rec[0];
        uint16_t value = get16(rec + 1);
        if (checksum_seen && code != 15)
            return fail(why, room, "the checksum record must directly precede End", off);
        /* close the open channel when a structural record comes */
        if (chan && (code == 2 || code == 4 || code == 5 || code == 6 || code == 15)) {
            if ((cv.seen & 0x1E00) != 0x1E00)
                return fail(why, room, "a channel has no index, VID, PID or serial", chan_off);
            if (chan == 5) { in_v = cv; ends |= 1; } else { out_v = cv; ends |= 2; }
            chan = 0;
        }
        if (in_link && (code == 2 || code == 4 || code == 15)) {
            if (ends != 3) return fail(why, room, "a link lacks its input or output channel",
                                       link_off);
            if (g_nstored < MAX_STORED_LINKS) {
                cur.config = (uint8_t)cfg;
                to_end(&in_v, &cur.in, &cur.in_type, &cur.in_profile);
                to_end(&out_v, &cur.out, &cur.out_type, &cur.out_profile);
                g_stored[g_nstored++] = cur;
            }
            links_in_cfg++;
            in_link = 0;
        }
        if (cfg && (code == 2 || code == 15)) {
            if (link_count != links_in_cfg)
                return fail(why, room, "# of links disagrees with the links that follow", lc_off);
            nconfigs++;
            cfg = 0;
        }
        switch (code) {
        case 1:
            if (count >= 0 || off) return fail(why, room, "# of configurations must come first", off);
            count = value; count_off = off;
            break;
        case 2:
            if (count < 0) return fail(why, room, "Configuration before # of configurations", off);
            if (value < 1) return fail(why, room, "configuration index counts from 1", off);
            cfg = value; link_count = -1; links_in_cfg = 0;
            break;
        case 3:
            if (!cfg || link_count >= 0 || in_link)
                return fail(why, room, "# of links must follow its Configuration", off);
            link_count = value; lc_off = off;
            break;
        case 4:
            if (!cfg || link_count < 0) return fail(why, room, "Channel link outside a configuration", off);
            if (value < 1) return fail(why, room, "link index counts from 1", off);
            in_link = 1; ends = 0; link_off = off;
            break;
        case 5: case 6:
            if (!in_link) return fail(why, room, "a channel outside a link", off);
            if (ends & (code == 5 ? 1 : 2)) return fail(why, room, "a second channel of one kind", off);
            chan = code; chan_off = off;
            memset(&cv, 0, sizeof cv);
            break;
        case 7: case 8: case 9: case 10: case 11: case 12: case 13: case 14:
            if (!chan) return fail(why, room, "a value record outside a channel", off);
            if (cv.seen & (1u << code)) return fail(why, room, "a value twice in one channel", off);
            if (code == 9 && (value < 1 || value > 255))
                return fail(why, room, "channel index out of range 1..255", off);
            cv.seen |= (uint16_t)(1u << code);
            cv.v[code] = value;
            break;
        case 15:
            if (count < 0) return fail(why, room, "End before # of configurations", off);
            if (count != nconfigs)
                return fail(why, room, "# of configurations disagrees with what follows", count_off);
            return 0;
        case 16:
            if (value != crc) return fail(why, room, "checksum mismatch", off);
            checksum_seen = 1;
            break;
        default:
            break;   /* unknown codes are skipped (and kept in the stored bytes) */
        }
        crc = crc16_update(crc, rec, 3);
    }
    return fail(why, room, len % 3 ? "truncated record" : "no End record", len);
}
