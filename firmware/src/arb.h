/* The reference arbitrator's tables and the calls between its modules (C99, no heap).
 *
 * Every table is a static array sized by a #define below (override with -D): devices ever
 * bound, channels of all devices, links, the stored configuration's links, a plan's actions.
 * Devices and channels stay in their tables when a device leaves (present = 0), as in PDCP
 * Studio's model: its links become dead links that the duty cycle repairs.
 */
#ifndef PDCP_ARB_H
#define PDCP_ARB_H

#include <stdint.h>
#include <stddef.h>

#ifdef __AVR__
#  ifndef MAX_DEVICES
#    define MAX_DEVICES 10
#  endif
#  ifndef MAX_CHANNELS
#    define MAX_CHANNELS 40
#  endif
#  ifndef MAX_LINKS
#    define MAX_LINKS 24
#  endif
#  ifndef DESC_MAX
#    define DESC_MAX 20
#  endif
#  ifndef CH_DESC_MAX
#    define CH_DESC_MAX 12
#  endif
#  ifndef VALUE_MAX
#    define VALUE_MAX 128
#  endif
#  ifndef MAX_VISIT
#    define MAX_VISIT 24
#  endif
#  ifndef MAX_CH_PER_DEVICE
#    define MAX_CH_PER_DEVICE 16
#  endif
#  ifndef MEM_CAPACITY
#    define MEM_CAPACITY 1000u
#  endif
#else
#  ifndef MAX_DEVICES
#    define MAX_DEVICES 64
#  endif
#  ifndef MAX_CHANNELS
#    define MAX_CHANNELS 192
#  endif
#  ifndef MAX_LINKS
#    define MAX_LINKS 128
#  endif
#  ifndef DESC_MAX
#    define DESC_MAX 40
#  endif
#  ifndef CH_DESC_MAX
#    define CH_DESC_MAX 24
#  endif
#  ifndef VALUE_MAX
#    define VALUE_MAX 512
#  endif
#endif
#ifndef MAX_STORED_LINKS
#  define MAX_STORED_LINKS MAX_LINKS
#endif
#ifndef MAX_ACTIONS
#  define MAX_ACTIONS (MAX_LINKS + MAX_LINKS / 2)
#endif
#ifndef MAX_CH_PER_DEVICE
#  define MAX_CH_PER_DEVICE 32 /* required/desired bitmaps are 32 bits: channels 0..31 */
#endif
#ifndef MAX_VISIT
#  define MAX_VISIT 128        /* inputs tried in one intelligently_connect */
#endif
#define NODE_ID_MIN 1
#define NODE_ID_MAX 254        /* node IDs shared by devices and output channels */

/* Timing (milliseconds), PDCP Studio's constants (bus/arbitrator/common.py, claim.py). */
#ifndef RESPONSE_TIMEOUT_MS
#  define RESPONSE_TIMEOUT_MS 150  /* one attempt (the QEMU build: 300) */
#endif
#define REQUEST_RETRIES 4
#define ARB_BEACON_MS 500          /* reference §5: mode-1 Device Beacon, node 0 */
#ifndef LISTEN_MS
#  define LISTEN_MS (22 * ARB_BEACON_MS / 10) /* two intervals and a margin (claim.py); QEMU: 3 s */
#endif
#define RECLAIM_MS (5 * ARB_BEACON_MS)
#define UNREAD_BEACON_MS 1000
#define MISSED_BEACONS_X2 7        /* gone after 3.5 beacon intervals (3 missed + grace) */
#ifndef PRESENCE_MIN_MS
#  define PRESENCE_MIN_MS 0        /* but never sooner than this (the QEMU build: 1500 ms) */
#endif
#define BIND_HOLD_MS 2000
#define FOREIGN_HOLD_MS 1000
#define UNKNOWN_RESET_MS 1000
#ifndef STARTUP_QUIET_MS
#  define STARTUP_QUIET_MS 500      /* listing 4.1's x ms (the QEMU build: 1500) */
#endif
#define STARTUP_MAX_WAIT_MS 10000
#define DUTY_QUIET_MS 50
#define SETUP_ATTEMPTS 3
#define SETUP_RETRY_MS 5000       /* a device whose set-ups all failed is tried again after */
#define INTERLOCK_MS 2000

typedef struct { uint16_t vid, pid, serial; } dev_key_t;
typedef struct { uint16_t vid, pid, serial; uint8_t index; } ch_ref_t;
typedef struct { ch_ref_t out, in; } link_t;

typedef struct {
    dev_key_t key;
    uint8_t used;
    uint8_t in_system;     /* set up at least once (or named by the stored configuration) */
    uint8_t present;
    uint8_t node_id;       /* 0: none */
    uint8_t set_up;        /* the current binding has been read and installed */
    uint8_t needs_setup;
    uint8_t setup_failures;
    uint32_t setup_failed_at;  /* when its last set-up attempt failed */
    uint8_t nch;           /* Number of Data Channels */
    uint16_t fw, hw, dtype, dprofile, beacon_ms, ack_ms, bind_ms;
    uint32_t ean_lo, ean_hi;
    uint32_t last_seen;
    uint8_t desc_len;
    char desc[DESC_MAX];
} device_t;

typedef struct {
    uint16_t vid, pid, serial;
    uint8_t index;
    uint16_t type, profile;
} source_t;

typedef struct {
    uint8_t used;
    uint8_t dev;           /* device slot */
    uint8_t index;
    uint8_t dir;           /* 1 input, 2 output */
    uint8_t enabled;
    uint16_t type, profile, term_profile;
    uint32_t req, des;     /* bit i = channel index i */
    source_t src;
    uint8_t desc_len;
    char desc[CH_DESC_MAX];
} channel_t;

#define DIR_IN 1
#define DIR_OUT 2
#define TYPE_SOLE 0x0200
#define TYPE_TERMINAL 0x0100

extern device_t g_dev[MAX_DEVICES];
extern channel_t g_ch[MAX_CHANNELS];
extern link_t g_links[MAX_LINKS];
extern uint16_t g_nlinks;

/* -- util.c ----------------------------------------------------------------------------- */
uint16_t crc16_update(uint16_t crc, const uint8_t *data, size_t len);
uint16_t crc16(const uint8_t *data, size_t len);
uint32_t crc32_update(uint32_t crc, const uint8_t *data, size_t len); /* zlib's, pre/post ~ */
int key_eq(const dev_key_t *a, const dev_key_t *b);
int key_cmp(const dev_key_t *a, const dev_key_t *b);
int ref_cmp(const ch_ref_t *a, const ch_ref_t *b);
int link_cmp(const link_t *a, const link_t *b);
int ref_on(const ch_ref_t *r, const dev_key_t *k);
void put16(uint8_t *p, uint16_t v);
void put32(uint8_t *p, uint32_t v);
uint16_t get16(const uint8_t *p);
uint32_t get32(const uint8_t *p);
int put_ref(uint8_t *p, const ch_ref_t *r);   /* 7 bytes */
void get_ref(const uint8_t *p, ch_ref_t *r);
int fmt_text(char *out, int room, const char *fmt, ...); /* %s %u %x(04) %r (ref) %k (key) */
#ifdef __AVR__
/* On the AVR the format strings stay in flash (string literals would be copied to RAM). */
#  include <avr/pgmspace.h>
int fmt_text_P(char *out, int room, const char *fmt, ...);
#  define fmt_text(out, room, fmt, ...) fmt_text_P(out, room, PSTR(fmt), ##__VA_ARGS__)
#  define FMT_BYTE(p) pgm_read_byte(p)
#endif

/* -- tables.c (devices, channels, links, node IDs) -------------------------------------- */
int dev_find(const dev_key_t *k);                 /* slot or -1 */
int dev_add(const dev_key_t *k);                  /* slot or -1 when full */
int ch_find(const ch_ref_t *r);                   /* slot or -1 */
int ch_of(int dev, uint8_t index);                /* slot or -1 */
void ch_ref(int ch, ch_ref_t *r);
int ch_present(int ch);                           /* device present (outputs: with a node ID) */
int ref_present(const ch_ref_t *r, uint8_t dir);  /* 0 for an absent or wrong-direction one */
int link_find(const link_t *l);
int link_add(const link_t *l);                    /* 0 ok, -1 full */
void link_del(int i);
int link_source_of(const ch_ref_t *in, int live_only);  /* link index or -1 */
uint8_t node_of_output(int dev, uint8_t index);   /* 0: none */
uint8_t node_output_id(const ch_ref_t *r);
void nodes_release_device(int dev);
int nodes_take_output(int dev, uint8_t index);    /* node ID or 0 when exhausted */
void nodes_clear(void);
int nodes_bind(const dev_key_t *k, uint8_t asked, uint32_t now, uint8_t *grant); /* 1 grant, 2 suggest, 0 none */
void nodes_expire(uint32_t now);
int nodes_owner_dev(uint8_t id);                  /* device slot bound to id, or -1 */
int nodes_is_channel(uint8_t id);
int nodes_is_free(uint8_t id);
void nodes_hear_foreign(uint8_t id, uint32_t now);
int nodes_exhausted_reported(int dev);

/* -- can.c: requests to devices (blocking; the bus and host link are pumped meanwhile) -- */
#define REQ_OK 0
#define REQ_REFUSED 1
#define REQ_TIMEOUT 2
#define REQ_ABSENT 3
#define REQ_NOWRITE 4
void can_send(uint16_t id, const uint8_t *data, uint8_t len);
void can_send_arb(uint8_t node, const uint8_t *data, uint8_t len);
int req_get(uint8_t node, uint8_t param, uint8_t chan, uint8_t *value, uint16_t room,
            uint16_t *len);
int req_set(uint8_t node, uint8_t param, uint8_t chan, const uint8_t *value, uint16_t len);
int req_simple(uint8_t node, uint8_t code, const uint8_t *body, uint8_t blen);
int req_on_frame(uint16_t id, const uint8_t *data, uint8_t len); /* 1: taken by the waiter */

/* -- arb.c: the bus side ----------------------------------------------------------------- */
extern uint8_t g_may_write;     /* listening is over and no other arbitrator is heard */
extern uint8_t g_other_heard;
extern uint8_t g_startup_done;
extern uint16_t g_changes;
void arb_init(void);
void pump(void);                /* one round of background work: bytes in, frames in, timers */
void arb_step(void);            /* main-loop work: set-ups, presence, start-up, duty cycle */
int arb_settled(void);
int arb_add_link(const link_t *l, char *why, int room);    /* host-link status or 0 */
int arb_remove_link(const link_t *l, char *why, int room);
int arb_wire_add(const link_t *l);         /* 0 ok, else REQ_* */
int arb_wire_remove(const link_t *l);
int arb_set_param(int dev, uint8_t param, uint8_t chan, const uint8_t *v, uint16_t len);
int arb_get_param(int dev, uint8_t param, uint8_t chan, uint8_t *v, uint16_t room,
                  uint16_t *len);
int arb_managed(int dev, uint8_t param, uint8_t chan);
int arb_hold(const dev_key_t *keys, int n, int *refused);  /* suspend each; REQ_* */
void arb_release(const dev_key_t *keys, int n);
void arb_reset_all(void);

/* -- memory.c: the two-slot stored configuration and the policy ------------------------ */
#ifndef MEM_CAPACITY
#  define MEM_CAPACITY 8192u
#endif
int mem_current(uint32_t *len, uint16_t *crc, uint16_t *flags);   /* slot or -1 */
int mem_read(uint32_t offset, uint8_t *buf, uint32_t len);        /* current payload */
int mem_decode_slot(int slot, uint32_t len, char *why, int room);  /* → g_stored; 0 ok */
int mem_begin(void);                              /* the spare slot: returns it */
int mem_write_chunk(uint32_t offset, const uint8_t *buf, uint32_t len);
int mem_commit(uint32_t len, uint16_t flags);     /* header last; 0 ok */
int mem_policy_autoconfigure(void);
int mem_write_policy(int autoconfigure);
int mem_copy_area(int area, uint32_t offset, uint32_t len); /* area bytes → spare slot */

/* -- config.c: reference §3 codec over an NVM area ------------------------------------- */
typedef struct {
    uint8_t config;          /* configuration index (from 1) */
    ch_ref_t out, in;
    uint16_t out_type, out_profile, in_type, in_profile;
} stored_link_t;
extern stored_link_t g_stored[MAX_STORED_LINKS];
extern uint16_t g_nstored;
/* Decode len bytes of an area (slot area, or -1 for the current slot) into g_stored;
 * 0 ok, else an error with the reason in why. */
int config_decode(int area, uint32_t base, uint32_t len, char *why, int room);

/* -- profile.c: the profile layer (listings 4.1–4.9) ------------------------------------- */
void profile_startup(void);
void profile_duty_cycle(void);
void profile_note_present(void);

/* -- hostlink.c ------------------------------------------------------------------------ */
void hl_init(void);
void hl_rx(const uint8_t *data, int len);
void hl_poll(void);
void hl_service(void);          /* main loop: answer a request that arrived */
void hl_event(const uint8_t *msg, int len);
int hl_greeted(void);
void hl_event_device(uint8_t code, int dev);
void hl_event_left(int dev, uint32_t silent_ms, uint16_t interval_ms, const char *why);
void hl_event_link(uint8_t code, const link_t *l);
void hl_event_error(uint8_t kind, const char *text);

/* -- monitor.c: FRAMES and CHANNEL_COUNTS (MONITOR 0 leaves it out) -------------------- */
#ifndef MONITOR
#  ifdef __AVR__
#    define MONITOR 0
#  else
#    define MONITOR 1
#  endif
#endif
uint16_t mon_configure(uint8_t flags, uint8_t period);
void mon_stop(void);
void mon_frame(uint16_t id, const uint8_t *data, uint8_t len);
int mon_take(uint8_t *msg);

/* -- txn.c: TRANSACT_RUN ---------------------------------------------------------------- */
int txn_run(uint32_t len, uint32_t *result_len, uint16_t *result_crc, char *why, int room);

#endif
