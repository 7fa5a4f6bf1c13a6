/* The stored configuration in non-volatile memory: two slots, safe against power cuts.
 *
 * The layout is PDCP Studio's (bus/arbitrator/memory.py), so a memory image moves between
 * this firmware and `pdcp-studio arbitrator --memory FILE`: each slot is a 24-byte header
 * (magic "PDCM", format version 1 u16, policy flags u16, generation u64, payload length u32,
 * CRC-32 of generation, length, payload and — when any is set — the flags) and the payload,
 * the reference §3 bytes.  A write goes to the slot not holding the newest valid generation:
 * payload first, header last; until the header is whole that slot fails its CRC and the
 * reader takes the other one.  Policy flag 0x0001: never autoconfigure.
 */
#include <string.h>
#include "arb.h"
#include "port.h"

#define HEADER 24
#define FLAG_NO_AUTOCONFIGURE 0x0001

static int cur_slot = -1;
static uint32_t cur_len, cur_gen;
static uint16_t cur_crc16, cur_flags;
static int spare = -1;

static int check_slot(int slot, uint32_t *gen, uint32_t *len, uint16_t *flags, uint16_t *c16)
{
    uint8_t h[HEADER], buf[64], tail[8];
    if (port_nvm_read(slot, 0, h, HEADER)) return 0;
    if (memcmp(h, "PDCM", 4) || get16(h + 4) != 1) return 0;
    uint32_t length = get32(h + 16);
    if (length > MEM_CAPACITY || get32(h + 12) != 0) return 0;
    uint32_t crc = 0;
    memcpy(tail, h + 8, 4);            /* generation u64 (low word first) */
    memcpy(tail + 4, h + 12, 4);
    crc = crc32_update(0, tail, 8);
    crc = crc32_update(crc, h + 16, 4);
    uint16_t crc16v = 0xFFFF;
    for (uint32_t off = 0; off < length; off += sizeof buf) {
        uint32_t n = length - off < sizeof buf ? length - off : sizeof buf;
        if (port_nvm_read(slot, HEADER + off, buf, n)) return 0;
        crc = crc32_update(crc, buf, n);
        crc16v = crc16_update(crc16v, buf, n);
    }
    uint16_t fl = get16(h + 6);
    if (fl) {
        uint8_t f[2]; put16(f, fl);
        crc = crc32_update(crc, f, 2);
    }
    if (crc != get32(h + 20)) return 0;
    *gen = get32(h + 8); *len = length; *flags = fl; *c16 = crc16v;
    return 1;
}

static void scan(void)
{
    uint32_t gen, len; uint16_t flags, c;
    cur_slot = -1;
    for (int s = 0; s < 2; s++) {
        if (check_slot(s, &gen, &len, &flags, &c) && (cur_slot < 0 || gen > cur_gen)) {
            char why[8];
            if (len && config_decode(s, HEADER, len, why, sizeof why)) continue;
            cur_slot = s; cur_gen = gen; cur_len = len; cur_flags = flags; cur_crc16 = c;
        }
    }
}

int mem_current(uint32_t *len, uint16_t *crc, uint16_t *flags)
{
    static int scanned;
    if (!scanned) { scan(); scanned = 1; }
    if (len) *len = cur_slot < 0 ? 0 : cur_len;
    if (crc) *crc = cur_slot < 0 ? 0xFFFF : cur_crc16;
    if (flags) *flags = cur_slot < 0 ? 0 : cur_flags;
    return cur_slot;
}

int mem_read(uint32_t offset, uint8_t *buf, uint32_t len)
{
    if (mem_current(0, 0, 0) < 0) return -1;
    return port_nvm_read(cur_slot, HEADER + offset, buf, len);
}

/* A slot's payload decoded into g_stored (the configuration a transaction replaced: the
 * slot it was current in until the commit); 0 ok. */
int mem_decode_slot(int slot, uint32_t len, char *why, int room)
{
    return slot < 0 || len > MEM_CAPACITY ? -1 : config_decode(slot, HEADER, len, why, room);
}

int mem_begin(void)
{
    spare = mem_current(0, 0, 0) == 0 ? 1 : 0;
    return spare;
}

int mem_write_chunk(uint32_t offset, const uint8_t *buf, uint32_t len)
{
    if (spare < 0 || offset + len > MEM_CAPACITY) return -1;
    return port_nvm_write(spare, HEADER + offset, buf, len);
}

int mem_commit(uint32_t len, uint16_t flags)
{
    uint8_t h[HEADER], buf[64], f[2];
    uint32_t gen = (mem_current(0, 0, 0) < 0 ? 0 : cur_gen) + 1;
    if (spare < 0 || len > MEM_CAPACITY) return -1;
    memcpy(h, "PDCM", 4);
    put16(h + 4, 1); put16(h + 6, flags);
    put32(h + 8, gen); put32(h + 12, 0); put32(h + 16, len);
    uint32_t crc = crc32_update(0, h + 8, 12);
    for (uint32_t off = 0; off < len; off += sizeof buf) {
        uint32_t n = len - off < sizeof buf ? len - off : sizeof buf;
        if (port_nvm_read(spare, HEADER + off, buf, n)) return -1;
        crc = crc32_update(crc, buf, n);
    }
    if (flags) { put16(f, flags); crc = crc32_update(crc, f, 2); }
    put32(h + 20, crc);
    if (port_nvm_sync()) return -1;
    if (port_nvm_write(spare, 0, h, HEADER / 2) || port_nvm_write(spare, HEADER / 2, h + HEADER / 2,
                                                                  HEADER / 2))
        return -1;
    if (port_nvm_sync()) return -1;
    int slot = spare;
    spare = -1;
    scan();
    return cur_slot == slot && cur_gen == gen ? 0 : -1;
}

int mem_policy_autoconfigure(void)
{
    uint16_t flags;
    mem_current(0, 0, &flags);
    return !(flags & FLAG_NO_AUTOCONFIGURE);
}

/* An empty collection in the reference §3 format: count 0, checksum, End. */
static uint32_t empty_collection(uint8_t *out)
{
    out[0] = 1; out[1] = 0; out[2] = 0;
    uint16_t c = crc16(out, 3);
    out[3] = 16; put16(out + 4, c);
    out[6] = 15; out[7] = 0; out[8] = 0;
    return 9;
}

int mem_write_policy(int autoconfigure)
{
    uint32_t len; uint16_t flags;
    uint8_t buf[64];
    int slot = mem_current(&len, 0, &flags);
    flags = (uint16_t)(flags & ~FLAG_NO_AUTOCONFIGURE);
    if (!autoconfigure) flags |= FLAG_NO_AUTOCONFIGURE;
    mem_begin();
    if (slot < 0 || !len) {
        len = empty_collection(buf);
        if (mem_write_chunk(0, buf, len)) return -1;
    } else {
        for (uint32_t off = 0; off < len; off += sizeof buf) {
            uint32_t n = len - off < sizeof buf ? len - off : sizeof buf;
            if (port_nvm_read(slot, HEADER + off, buf, n) || mem_write_chunk(off, buf, n))
                return -1;
        }
    }
    return mem_commit(len, flags);
}

int mem_copy_area(int area, uint32_t offset, uint32_t len)
{
    uint8_t buf[64];
    for (uint32_t off = 0; off < len; off += sizeof buf) {
        uint32_t n = len - off < sizeof buf ? len - off : sizeof buf;
        if (port_nvm_read(area, offset + off, buf, n) || mem_write_chunk(off, buf, n))
            return -1;
    }
    return 0;
}
