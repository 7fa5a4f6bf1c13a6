/* The lm3s6965evb port (QEMU -M lm3s6965evb).
 *
 * UART0: the host link (a pty on the host).  UART1: CAN frames as SLCAN text, bridged to a
 * python-can bus by `pdcp-studio can-bridge`.  SysTick: the millisecond tick (QEMU runs the
 * board at 12 MHz out of reset: reload 12000) as a fallback; the host's clock through
 * semihosting SYS_ELAPSED first (see port_millis).  Non-volatile memory: a file on the host through
 * ARM semihosting (QEMU -semihosting-config enable=on,target=native,arg=pdcp-fw,arg=FILE),
 * laid out as PDCP Studio's memory file (slot A at 0, slot B at 24 + 1 MiB, as
 * bus/arbitrator/memory.py) so `--memory FILE` images move between the two; the transaction
 * areas follow at the next multiples.  Without a file argument the areas live in RAM (small).
 */
#include <stdint.h>
#include <string.h>
#include "../../src/port.h"
#include "../../src/arb.h"
#include "../common/slcan.h"

#define REG(a) (*(volatile uint32_t *)(a))
#define UART0 0x4000C000u
#define UART1 0x4000D000u
#define UART_DR 0x000
#define UART_FR 0x018
#define UART_IBRD 0x024
#define UART_FBRD 0x028
#define UART_LCRH 0x02C
#define UART_CTL 0x030
#define FR_RXFE 0x10
#define FR_TXFF 0x20
#define SYSCTL_RCGC1 0x400FE104u

static volatile uint32_t ticks;

void systick_handler(void) { ticks++; }

static int semi(int op, void *arg)
{
    register int r0 __asm__("r0") = op;
    register void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

static void uart_init(uint32_t base)
{
    REG(base + UART_CTL) = 0;
    REG(base + UART_IBRD) = 6;     /* 115200 at 12 MHz (the rate means nothing on a pty) */
    REG(base + UART_FBRD) = 33;
    REG(base + UART_LCRH) = 0x70;  /* 8N1, FIFOs on */
    REG(base + UART_CTL) = 0x301;  /* UART, TX, RX enabled */
}

static int nvm_fd = -1;
static char nvm_path[200];
#define SLOT_STRIDE (24u + (1u << 20))
#define RAM_AREA 1024u
static uint8_t ram_nvm[NVM_AREAS][RAM_AREA];

void port_init(void)
{
    REG(SYSCTL_RCGC1) |= 3;
    uart_init(UART0);
    uart_init(UART1);
    REG(0xE000E014) = 12000 - 1;
    REG(0xE000E018) = 0;
    REG(0xE000E010) = 7;
    /* the memory file from the semihosting command line: "pdcp-fw FILE" */
    static char cmd[220];
    uint32_t args[2] = { (uint32_t)cmd, sizeof cmd };
    if (semi(0x15, args) == 0) {
        const char *p = cmd;
        while (*p && *p != ' ') p++;
        while (*p == ' ') p++;
        if (*p) {
            strncpy(nvm_path, p, sizeof nvm_path - 1);
            uint32_t o[3] = { (uint32_t)nvm_path, 3, strlen(nvm_path) };   /* "r+b" */
            nvm_fd = semi(0x01, o);
            if (nvm_fd < 0) {
                o[1] = 7;                                                  /* "w+b": create */
                nvm_fd = semi(0x01, o);
            }
        }
    }
    memset(ram_nvm, 0xFF, sizeof ram_nvm);
}

/* Milliseconds from the host's clock (semihosting SYS_ELAPSED, microsecond ticks in QEMU):
 * QEMU's SysTick drops periods when the host is loaded, so a guest clock counted from it runs
 * slow and the link's 250 ms timeouts stretch. SysTick is the fallback. */
static int elapsed_ok = 1;
static uint32_t tick_hz;

uint32_t port_millis(void)
{
    if (elapsed_ok) {
        uint32_t t[2];
        if (!tick_hz) {
            int hz = semi(0x31, 0);               /* SYS_TICKFREQ */
            if (hz <= 0) { elapsed_ok = 0; return ticks; }
            tick_hz = (uint32_t)hz;
        }
        if (semi(0x30, t) == 0) {                 /* SYS_ELAPSED: 64-bit tick count */
            uint64_t n = ((uint64_t)t[1] << 32) | t[0];
            return (uint32_t)(n / (tick_hz / 1000u));
        }
        elapsed_ok = 0;
    }
    return ticks;
}

int port_host_read(uint8_t *buf, int max)
{
    int n = 0;
    while (n < max && !(REG(UART0 + UART_FR) & FR_RXFE)) buf[n++] = (uint8_t)REG(UART0 + UART_DR);
    return n;
}

static void uart_write(uint32_t base, const uint8_t *buf, int len)
{
    for (int i = 0; i < len; i++) {
        while (REG(base + UART_FR) & FR_TXFF) {}
        REG(base + UART_DR) = buf[i];
    }
}

void port_host_write(const uint8_t *buf, int len) { uart_write(UART0, buf, len); }

static slcan_rx_t can_rx;
static int can_open;

int port_can_ready(void)
{
    uint16_t id; uint8_t d[8], n;
    while (!can_open && port_can_read(&id, d, &n)) {}   /* frames before "O": not ours */
    return can_open;
}

int port_can_read(uint16_t *id, uint8_t *data, uint8_t *len)
{
    while (!(REG(UART1 + UART_FR) & FR_RXFE)) {
        char c = (char)REG(UART1 + UART_DR);
        int r = slcan_feed(&can_rx, c, id, data, len);
        if (r == 1) return 1;
        if (r >= 2) uart_write(UART1, (const uint8_t *)"\r", 1);
        if (r == 3) can_open = 1;
    }
    return 0;
}

void port_can_write(uint16_t id, const uint8_t *data, uint8_t len)
{
    char line[24];
    int n = slcan_format(line, id, data, len);
    uart_write(UART1, (const uint8_t *)line, n);
}

uint32_t port_nvm_capacity(int area)
{
    if (nvm_fd < 0) return area < 2 ? RAM_AREA : RAM_AREA;
    return area < 2 ? 24u + MEM_CAPACITY : area == 2 ? 16384u : 8192u;
}

int port_nvm_read(int area, uint32_t offset, uint8_t *buf, uint32_t len)
{
    if (area < 0 || area >= NVM_AREAS || offset + len > port_nvm_capacity(area)) return -1;
    if (nvm_fd < 0) { memcpy(buf, ram_nvm[area] + offset, len); return 0; }
    uint32_t s[2] = { (uint32_t)nvm_fd, area * SLOT_STRIDE + offset };
    if (semi(0x0A, s)) { memset(buf, 0, len); return 0; }   /* past the end: blank */
    uint32_t r[3] = { (uint32_t)nvm_fd, (uint32_t)buf, len };
    int left = semi(0x06, r);
    if (left < 0) return -1;
    if (left) memset(buf + (len - (uint32_t)left), 0, (uint32_t)left);   /* past the end: blank */
    return 0;
}

int port_nvm_write(int area, uint32_t offset, const uint8_t *buf, uint32_t len)
{
    if (area < 0 || area >= NVM_AREAS || offset + len > port_nvm_capacity(area)) return -1;
    if (nvm_fd < 0) { memcpy(ram_nvm[area] + offset, buf, len); return 0; }
    uint32_t s[2] = { (uint32_t)nvm_fd, area * SLOT_STRIDE + offset };
    if (semi(0x0A, s)) return -1;
    uint32_t w[3] = { (uint32_t)nvm_fd, (uint32_t)buf, len };
    return semi(0x05, w) ? -1 : 0;
}

int port_nvm_sync(void) { return 0; }   /* semihosting writes reach the host file at once */

void port_log(const char *text)
{
    semi(0x04, (void *)text);
    semi(0x04, (void *)"\n");
}
