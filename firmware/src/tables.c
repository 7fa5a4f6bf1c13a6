/* The arbitrator's tables: devices, channels, links, and the node-ID pool (reference §1).
 *
 * One pool of node IDs 1..254 is shared by devices and their output channels.  A bind request
 * asking for a free ID (or the one the device holds) is granted at once; otherwise the lowest
 * free ID is suggested and held for that device for BIND_HOLD_MS (bus/arbitrator/nodes.py).
 * IDs heard from devices bound by an earlier arbitrator stay out of the pool while heard.
 */
#include <string.h>
#include "arb.h"

device_t g_dev[MAX_DEVICES];
channel_t g_ch[MAX_CHANNELS];
link_t g_links[MAX_LINKS];
uint16_t g_nlinks;

#define OWN_FREE 0
#define OWN_DEVICE 1
#define OWN_OUTPUT 2
#define OWN_FOREIGN 3
#define OWN_HELD 4

static uint8_t own_kind[NODE_ID_MAX + 1];
static uint8_t own_dev[NODE_ID_MAX + 1];
static uint8_t own_idx[NODE_ID_MAX + 1];
static uint16_t own_since[NODE_ID_MAX + 1];   /* held: when suggested; foreign: last heard
                                                * (in units of 16 ms, compared modulo 2^16) */
#define T16(now) ((uint16_t)((now) >> 4))
static uint8_t exhausted_told[(MAX_DEVICES + 7) / 8];

int dev_find(const dev_key_t *k)
{
    for (int i = 0; i < MAX_DEVICES; i++)
        if (g_dev[i].used && key_eq(&g_dev[i].key, k)) return i;
    return -1;
}

int dev_add(const dev_key_t *k)
{
    int i = dev_find(k);
    if (i >= 0) return i;
    for (i = 0; i < MAX_DEVICES; i++) {
        if (!g_dev[i].used) {
            memset(&g_dev[i], 0, sizeof g_dev[i]);
            g_dev[i].used = 1;
            g_dev[i].key = *k;
            return i;
        }
    }
    /* Full: reuse a device that is neither present, bound nor named by a link. */
    for (i = 0; i < MAX_DEVICES; i++) {
        device_t *d = &g_dev[i];
        int named = 0;
        if (d->present || d->node_id) continue;
        for (uint16_t l = 0; l < g_nlinks && !named; l++)
            named = ref_on(&g_links[l].out, &d->key) || ref_on(&g_links[l].in, &d->key);
        if (named) continue;
        for (int c = 0; c < MAX_CHANNELS; c++)
            if (g_ch[c].used && g_ch[c].dev == i) g_ch[c].used = 0;
        memset(d, 0, sizeof *d);
        d->used = 1;
        d->key = *k;
        return i;
    }
    return -1;
}

int ch_of(int dev, uint8_t index)
{
    for (int c = 0; c < MAX_CHANNELS; c++)
        if (g_ch[c].used && g_ch[c].dev == dev && g_ch[c].index == index) return c;
    return -1;
}

int ch_find(const ch_ref_t *r)
{
    dev_key_t k = { r->vid, r->pid, r->serial };
    int d = dev_find(&k);
    return d < 0 ? -1 : ch_of(d, r->index);
}

void ch_ref(int ch, ch_ref_t *r)
{
    const dev_key_t *k = &g_dev[g_ch[ch].dev].key;
    r->vid = k->vid; r->pid = k->pid; r->serial = k->serial; r->index = g_ch[ch].index;
}

int ch_present(int ch)
{
    const device_t *d = &g_dev[g_ch[ch].dev];
    if (!d->present) return 0;
    if (g_ch[ch].dir == DIR_OUT) return node_of_output(g_ch[ch].dev, g_ch[ch].index) != 0;
    return 1;
}

int ref_present(const ch_ref_t *r, uint8_t dir)
{
    int c = ch_find(r);
    return c >= 0 && g_ch[c].dir == dir && ch_present(c);
}

int link_find(const link_t *l)
{
    for (uint16_t i = 0; i < g_nlinks; i++)
        if (!link_cmp(&g_links[i], l)) return i;
    return -1;
}

int link_add(const link_t *l)
{
    if (link_find(l) >= 0) return 0;
    if (g_nlinks >= MAX_LINKS) return -1;
    g_links[g_nlinks++] = *l;
    return 0;
}

void link_del(int i)
{
    if (i < 0 || i >= (int)g_nlinks) return;
    g_nlinks--;
    for (int j = i; j < (int)g_nlinks; j++) g_links[j] = g_links[j + 1];
}

int link_source_of(const ch_ref_t *in, int live_only)
{
    for (uint16_t i = 0; i < g_nlinks; i++) {
        if (ref_cmp(&g_links[i].in, in)) continue;
        if (!live_only || (ref_present(&g_links[i].out, DIR_OUT) && ref_present(in, DIR_IN)))
            return i;
    }
    return -1;
}

/* -- node IDs ----------------------------------------------------------------------------- */
uint8_t node_of_output(int dev, uint8_t index)
{
    for (int id = NODE_ID_MIN; id <= NODE_ID_MAX; id++)
        if (own_kind[id] == OWN_OUTPUT && own_dev[id] == dev && own_idx[id] == index)
            return (uint8_t)id;
    return 0;
}

uint8_t node_output_id(const ch_ref_t *r)
{
    dev_key_t k = { r->vid, r->pid, r->serial };
    int d = dev_find(&k);
    return d < 0 ? 0 : node_of_output(d, r->index);
}

int nodes_is_free(uint8_t id)
{
    return id >= NODE_ID_MIN && id <= NODE_ID_MAX && own_kind[id] == OWN_FREE;
}

static int lowest_free(void)
{
    for (int id = NODE_ID_MIN; id <= NODE_ID_MAX; id++)
        if (own_kind[id] == OWN_FREE) return id;
    return 0;
}

void nodes_release_device(int dev)
{
    for (int id = NODE_ID_MIN; id <= NODE_ID_MAX; id++)
        if (own_kind[id] != OWN_FREE && own_kind[id] != OWN_FOREIGN && own_dev[id] == dev)
            own_kind[id] = OWN_FREE;
    g_dev[dev].node_id = 0;
}

int nodes_take_output(int dev, uint8_t index)
{
    int id = node_of_output(dev, index);
    if (id) return id;
    id = lowest_free();
    if (!id) return 0;
    own_kind[id] = OWN_OUTPUT; own_dev[id] = (uint8_t)dev; own_idx[id] = index;
    return id;
}

void nodes_clear(void)
{
    memset(own_kind, 0, sizeof own_kind);
    memset(exhausted_told, 0, sizeof exhausted_told);
    for (int i = 0; i < MAX_DEVICES; i++) g_dev[i].node_id = 0;
}

int nodes_owner_dev(uint8_t id)
{
    if (id < NODE_ID_MIN || id > NODE_ID_MAX) return -1;
    return own_kind[id] == OWN_DEVICE ? own_dev[id] : -1;
}

int nodes_is_channel(uint8_t id)
{
    return id >= NODE_ID_MIN && id <= NODE_ID_MAX && own_kind[id] == OWN_OUTPUT;
}

void nodes_hear_foreign(uint8_t id, uint32_t now)
{
    if (id < NODE_ID_MIN || id > NODE_ID_MAX) return;
    if (own_kind[id] == OWN_FREE) own_kind[id] = OWN_FOREIGN;
    if (own_kind[id] == OWN_FOREIGN) own_since[id] = T16(now);
}

int nodes_exhausted_reported(int dev)
{
    int told = exhausted_told[dev / 8] & (1 << (dev % 8));
    exhausted_told[dev / 8] |= (uint8_t)(1 << (dev % 8));
    return told != 0;
}

/* A bind request from key asking for `asked`: 1 grant, 2 suggest (held), 0 exhausted. */
int nodes_bind(const dev_key_t *k, uint8_t asked, uint32_t now, uint8_t *grant)
{
    int dev = dev_add(k);
    int held = 0;
    if (dev < 0) return 0;
    for (int id = NODE_ID_MIN; id <= NODE_ID_MAX; id++)
        if ((own_kind[id] == OWN_DEVICE || own_kind[id] == OWN_HELD) && own_dev[id] == dev)
            held = id;
    if (asked >= NODE_ID_MIN && asked <= NODE_ID_MAX && own_kind[asked] == OWN_FOREIGN)
        own_kind[asked] = OWN_FREE;   /* most likely that very device, reset and binding again */
    int g;
    if (asked == held || nodes_is_free(asked)) g = asked;
    else if (held) g = held;
    else g = lowest_free();
    if (!g) return 0;
    exhausted_told[dev / 8] &= (uint8_t)~(1 << (dev % 8));
    if (held && held != g) own_kind[held] = OWN_FREE;
    own_dev[g] = (uint8_t)dev;
    *grant = (uint8_t)g;
    if (g == asked) {
        own_kind[g] = OWN_DEVICE;
        return 1;
    }
    own_kind[g] = OWN_HELD;
    own_since[g] = T16(now);
    return 2;
}

void nodes_expire(uint32_t now)
{
    for (int id = NODE_ID_MIN; id <= NODE_ID_MAX; id++) {
        if (own_kind[id] == OWN_FOREIGN && (uint16_t)(T16(now) - own_since[id]) > FOREIGN_HOLD_MS / 16)
            own_kind[id] = OWN_FREE;
        else if (own_kind[id] == OWN_HELD && (uint16_t)(T16(now) - own_since[id]) > BIND_HOLD_MS / 16)
            own_kind[id] = OWN_FREE;
    }
}
