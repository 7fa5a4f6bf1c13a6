/* Small helpers: CRCs, little-endian fields, comparisons, a tiny text formatter. */
#include <stdarg.h>
#include "arb.h"

uint16_t crc16_update(uint16_t crc, const uint8_t *data, size_t len)
{
    /* CRC-16/CCITT-FALSE: poly 0x1021, init 0xFFFF, no reflection (crc("123456789") = 0x29B1) */
    while (len--) {
        crc ^= (uint16_t)(*data++) << 8;
        for (int i = 0; i < 8; i++)
            crc = (crc & 0x8000) ? (uint16_t)((crc << 1) ^ 0x1021) : (uint16_t)(crc << 1);
    }
    return crc;
}

uint16_t crc16(const uint8_t *data, size_t len) { return crc16_update(0xFFFF, data, len); }

uint32_t crc32_update(uint32_t crc, const uint8_t *data, size_t len)
{
    crc = ~crc;
    while (len--) {
        crc ^= *data++;
        for (int i = 0; i < 8; i++)
            crc = (crc & 1) ? (crc >> 1) ^ 0xEDB88320u : crc >> 1;
    }
    return ~crc;
}

int key_eq(const dev_key_t *a, const dev_key_t *b)
{
    return a->vid == b->vid && a->pid == b->pid && a->serial == b->serial;
}

int key_cmp(const dev_key_t *a, const dev_key_t *b)
{
    if (a->vid != b->vid) return a->vid < b->vid ? -1 : 1;
    if (a->pid != b->pid) return a->pid < b->pid ? -1 : 1;
    if (a->serial != b->serial) return a->serial < b->serial ? -1 : 1;
    return 0;
}

int ref_cmp(const ch_ref_t *a, const ch_ref_t *b)
{
    if (a->vid != b->vid) return a->vid < b->vid ? -1 : 1;
    if (a->pid != b->pid) return a->pid < b->pid ? -1 : 1;
    if (a->serial != b->serial) return a->serial < b->serial ? -1 : 1;
    if (a->index != b->index) return a->index < b->index ? -1 : 1;
    return 0;
}

int link_cmp(const link_t *a, const link_t *b)
{
    int c = ref_cmp(&a->out, &b->out);
    return c ? c : ref_cmp(&a->in, &b->in);
}

int ref_on(const ch_ref_t *r, const dev_key_t *k)
{
    return r->vid == k->vid && r->pid == k->pid && r->serial == k->serial;
}

void put16(uint8_t *p, uint16_t v) { p[0] = (uint8_t)v; p[1] = (uint8_t)(v >> 8); }
void put32(uint8_t *p, uint32_t v) { put16(p, (uint16_t)v); put16(p + 2, (uint16_t)(v >> 16)); }
uint16_t get16(const uint8_t *p) { return (uint16_t)(p[0] | (p[1] << 8)); }
uint32_t get32(const uint8_t *p) { return get16(p) | ((uint32_t)get16(p + 2) << 16); }

int put_ref(uint8_t *p, const ch_ref_t *r)
{
    put16(p, r->vid); put16(p + 2, r->pid); put16(p + 4, r->serial); p[6] = r->index;
    return 7;
}

void get_ref(const uint8_t *p, ch_ref_t *r)
{
    r->vid = get16(p); r->pid = get16(p + 2); r->serial = get16(p + 4); r->index = p[6];
}

static int emit(char *out, int room, int n, char c)
{
    if (n < room - 1) out[n] = c;
    return n + 1;
}

static int emit_u(char *out, int room, int n, uint32_t v, int width, int base)
{
    char tmp[12];
    int i = 0;
    do { tmp[i++] = "0123456789ABCDEF"[v % (uint32_t)base]; v /= (uint32_t)base; } while (v);
    while (i < width) tmp[i++] = '0';
    while (i) n = emit(out, room, n, tmp[--i]);
    return n;
}

/* %s text, %u unsigned, %x four hex digits, %k device key (a dev_key_t *), %r channel
 * reference (a ch_ref_t *), as PDCP Studio prints them: 2641/257/101 and 2641/257/101.1. */
#ifdef __AVR__
#  undef fmt_text
#  define fmt_text fmt_text_P
#else
#  define FMT_BYTE(p) (*(p))
#endif
int fmt_text(char *out, int room, const char *fmt, ...)
{
    va_list ap;
    int n = 0;
    va_start(ap, fmt);
    for (; FMT_BYTE(fmt); fmt++) {
        char f = (char)FMT_BYTE(fmt);
        if (f != '%') { n = emit(out, room, n, f); continue; }
        fmt++;
        f = (char)FMT_BYTE(fmt);
        if (f == 's') {
            const char *s = va_arg(ap, const char *);
            while (*s) n = emit(out, room, n, *s++);
        } else if (f == 'u') {
            n = emit_u(out, room, n, va_arg(ap, unsigned), 0, 10);
        } else if (f == 'x') {
            n = emit_u(out, room, n, va_arg(ap, unsigned), 4, 16);
        } else if (f == 'k' || f == 'r') {
            const ch_ref_t *r = va_arg(ap, const ch_ref_t *);
            n = emit_u(out, room, n, r->vid, 0, 10); n = emit(out, room, n, '/');
            n = emit_u(out, room, n, r->pid, 0, 10); n = emit(out, room, n, '/');
            n = emit_u(out, room, n, r->serial, 0, 10);
            if (f == 'r') { n = emit(out, room, n, '.'); n = emit_u(out, room, n, r->index, 0, 10); }
        } else {
            n = emit(out, room, n, f);
        }
    }
    va_end(ap);
    if (room > 0) out[n < room ? n : room - 1] = 0;
    return n < room ? n : room - 1;
}
