/* The POSIX port: the core on the build machine, for fast tests and debugging.
 *
 * The host link and the CAN side (SLCAN text, as on QEMU's UART1) are two new
 * pseudo-terminals, printed on stdout as "host link on /dev/pts/N" and "can on /dev/pts/M";
 * the non-volatile memory is the file named by $PDCP_FW_MEMORY (PDCP Studio's memory-file
 * layout), or RAM without one.  Logs go to stderr.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <termios.h>
#include "../../src/port.h"
#include "../../src/arb.h"
#include "../common/slcan.h"

static int host_fd = -1, can_fd = -1, nvm_fd = -1;
static struct timespec t0;
#define SLOT_STRIDE (24u + (1u << 20))
static uint8_t ram_nvm[NVM_AREAS][16384];

static int open_pty(const char *what)
{
    int fd = posix_openpt(O_RDWR | O_NOCTTY);
    if (fd < 0 || grantpt(fd) || unlockpt(fd)) { perror("pty"); exit(1); }
    struct termios t;
    tcgetattr(fd, &t);
    cfmakeraw(&t);
    tcsetattr(fd, TCSANOW, &t);
    fcntl(fd, F_SETFL, O_NONBLOCK);
    printf("%s on %s\n", what, ptsname(fd));
    fflush(stdout);
    return fd;
}

void port_init(void)
{
    clock_gettime(CLOCK_MONOTONIC, &t0);
    memset(ram_nvm, 0xFF, sizeof ram_nvm);
    const char *path = getenv("PDCP_FW_MEMORY");
    if (path && *path) nvm_fd = open(path, O_RDWR | O_CREAT, 0644);
    can_fd = open_pty("can");
    host_fd = open_pty("host link");
}

uint32_t port_millis(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    static uint32_t idle;
    if (++idle % 64 == 0) usleep(200);      /* a polling loop must not eat a CPU */
    return (uint32_t)((t.tv_sec - t0.tv_sec) * 1000 + (t.tv_nsec - t0.tv_nsec) / 1000000);
}

int port_host_read(uint8_t *buf, int max)
{
    ssize_t n = read(host_fd, buf, (size_t)max);
    return n > 0 ? (int)n : 0;
}

static void write_all(int fd, const void *buf, size_t len)
{
    const uint8_t *p = buf;
    while (len) {
        ssize_t n = write(fd, p, len);
        if (n < 0) { if (errno == EAGAIN) { usleep(100); continue; } return; }
        p += n; len -= (size_t)n;
    }
}

void port_host_write(const uint8_t *buf, int len) { write_all(host_fd, buf, (size_t)len); }

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
    char c;
    while (read(can_fd, &c, 1) == 1) {
        int r = slcan_feed(&can_rx, c, id, data, len);
        if (r == 1) return 1;
        if (r >= 2) write_all(can_fd, "\r", 1);
        if (r == 3) can_open = 1;
    }
    return 0;
}

void port_can_write(uint16_t id, const uint8_t *data, uint8_t len)
{
    char line[24];
    int n = slcan_format(line, id, data, len);
    write_all(can_fd, line, (size_t)n);
}

uint32_t port_nvm_capacity(int area)
{
    return area < 2 ? 24u + MEM_CAPACITY : area == 2 ? 16384u : 8192u;
}

int port_nvm_read(int area, uint32_t offset, uint8_t *buf, uint32_t len)
{
    if (area < 0 || area >= NVM_AREAS || offset + len > port_nvm_capacity(area)) return -1;
    if (nvm_fd < 0) { memcpy(buf, ram_nvm[area] + offset, len); return 0; }
    ssize_t n = pread(nvm_fd, buf, len, (off_t)area * SLOT_STRIDE + offset);
    if (n < 0) return -1;
    if ((uint32_t)n < len) memset(buf + n, 0, len - (uint32_t)n);
    return 0;
}

int port_nvm_write(int area, uint32_t offset, const uint8_t *buf, uint32_t len)
{
    if (area < 0 || area >= NVM_AREAS || offset + len > port_nvm_capacity(area)) return -1;
    if (nvm_fd < 0) { memcpy(ram_nvm[area] + offset, buf, len); return 0; }
    return pwrite(nvm_fd, buf, len, (off_t)area * SLOT_STRIDE + offset) == (ssize_t)len ? 0 : -1;
}

int port_nvm_sync(void) { return nvm_fd >= 0 ? fsync(nvm_fd) : 0; }

void port_log(const char *text) { fprintf(stderr, "pdcp-fw: %s\n", text); }
