/*
 * usb_hs.c - USB OTG HS in device mode on the DISCO's ULPI PHY (USB3320 on
 * the HS connector), FIFO ("slave") mode, interrupt-driven: the OTG_HS
 * interrupt (tdc_disco_usb_irq) takes bus resets, enumeration, the
 * project's protocol (firmware/tdc_usbproto.c) on endpoint 0 and bulk OUT
 * 0x01 packets into a ring that tdc_board_transport_read() drains, so the
 * host is served while a stage runs.  The frame loop's share
 * (tdc_disco_usb_poll, from transport_read and the vsync wait, with the
 * interrupt masked) is what may take long or touches the protocol state
 * the interrupt also uses: a DFU block's erase and program (up to 4 s per
 * sector), the next status report on bulk IN 0x81, and re-arming bulk OUT
 * once the ring has room for a packet again (the endpoint NAKs meanwhile:
 * nothing is dropped).
 *
 * RM0399 chapter "USB on-the-go high-speed (OTG_HS)" (a Synopsys DWC2
 * core): core soft reset, forced device mode, high speed with the ULPI
 * PHY, FIFO RAM split RX 2 KiB / EP0 TX 256 B / EP1 TX 512 B (of 4 KiB),
 * received packets popped through GRXSTSP and the endpoint-0 FIFO window.
 * ULPI pins (AF10): CK PA5, D0 PA3, D1 PB0, D2 PB1, D3 PB10, D4 PB11,
 * D5 PB12, D6 PB13, D7 PB5, STP PC0, NXT PH4, DIR PI11 (the USB3320 wiring
 * of ST's DISCO boards; to be checked against UM2411's schematic).
 *
 * Executed in tests/disco against a DWC2 register model with a scripted
 * host (enumeration, a bulk transfer into transport_read); not yet run on
 * a board.
 */
#include <stdint.h>
#include <string.h>

#include "board.h"
#include "disco.h"
#include "tdc_usbproto.h"

#define RCC(off) TDC_REG32(TDC_STM32_RCC + (off))
#define OTG(off) TDC_REG32(TDC_STM32_USB_OTG_HS + (off))
#define GPIO(port, off) TDC_REG32(TDC_STM32_GPIO(port) + (off))
#define FIFO(ep) TDC_REG32(TDC_STM32_USB_OTG_HS + 0x1000u * ((ep) + 1u))

enum {
    GAHBCFG = 0x008, GUSBCFG = 0x00C, GRSTCTL = 0x010, GINTSTS = 0x014, GINTMSK = 0x018, GRXSTSP = 0x020,
    GRXFSIZ = 0x024, DIEPTXF0 = 0x028, DIEPTXF1 = 0x104, DCFG = 0x800, DCTL = 0x804, DSTS = 0x808,
    DIEPCTL0 = 0x900, DIEPINT0 = 0x908, DIEPTSIZ0 = 0x910, DOEPCTL0 = 0xB00, DOEPINT0 = 0xB08, DOEPTSIZ0 = 0xB10
};
#define EP(reg, n) ((reg) + 0x20u * (n))
#define EPENA (1u << 31)
#define CNAK (1u << 26)
#define SNAK (1u << 27)
#define STALL (1u << 21)
#define USBAEP (1u << 15)
#define SD0PID (1u << 28)
#define BULK (2u << 18)
#define GINT_RXFLVL (1u << 4)
#define GINT_USBRST (1u << 12)
#define GINT_ENUMDNE (1u << 13)
#define HS_MPS 512u
#define RING_BYTES TDC_DISCO_USB_RING_BYTES

#define OTG_IRQ_WORD (TDC_STM32_OTG_HS_IRQN / 32u)
#define OTG_IRQ_BIT (1u << (TDC_STM32_OTG_HS_IRQN % 32u))

static tdc_usbp_t g_proto;
static uint8_t g_ring[RING_BYTES];
/* Free-running; head - tail = bytes held.  One writer each: the interrupt
 * moves head, the frame loop tail. */
static volatile uint32_t g_head, g_tail;
static volatile int g_out_parked;
_Static_assert((RING_BYTES & (RING_BYTES - 1u)) == 0u && RING_BYTES >= 2u * HS_MPS,
               "free-running ring indices need a power-of-two size of at least two packets"); /* bulk OUT left NAKing: the ring had no room for a packet */
static uint8_t g_setup[8];
static uint8_t g_ctl[TDC_DFU_TRANSFER_SIZE]; /* EP0 data stage in or out: a DFU block at most */
static uint32_t g_ctl_out_len, g_ctl_out_want;
static int g_configured;

static void ulpi_pins(void)
{
    static const struct {
        uint8_t port, pin;
    } pins[] = {{0, 3}, {0, 5}, {1, 0}, {1, 1}, {1, 5}, {1, 10}, {1, 11}, {1, 12}, {1, 13}, {2, 0}, {7, 4}, {8, 11}};
    RCC(0xE0) |= (1u << 0) | (1u << 1) | (1u << 2) | (1u << 7) | (1u << 8); /* GPIOA B C H I */
    (void)RCC(0xE0);
    for (uint32_t i = 0; i < sizeof pins / sizeof pins[0]; i++) {
        const uint32_t p = pins[i].port, n = pins[i].pin;
        const uint32_t afr = n < 8u ? 0x20u : 0x24u, sh = 4u * (n & 7u);
        GPIO(p, afr) = (GPIO(p, afr) & ~(0xFu << sh)) | (10u << sh); /* AF10 = OTG_HS ULPI */
        GPIO(p, 0x08) |= 3u << (2u * n);                             /* very high speed */
        GPIO(p, 0x00) = (GPIO(p, 0x00) & ~(3u << (2u * n))) | (2u << (2u * n));
    }
}

static int wait_otg(uint32_t off, uint32_t mask, uint32_t want)
{
    for (uint32_t i = 0; i < 1000000u; i++) {
        if ((OTG(off) & mask) == want) {
            return 1;
        }
    }
    return 0;
}

int tdc_disco_usb_init(const tdc_usbp_config_t *cfg)
{
    if (tdc_usbp_init(&g_proto, cfg) != TDC_OK) {
        return 0;
    }
    ulpi_pins();
    RCC(0xD8) |= (1u << 25) | (1u << 26); /* RCC_AHB1ENR: USB1OTGHSEN, USB1OTGHSULPIEN */
    (void)RCC(0xD8);
    if (!wait_otg(GRSTCTL, 1u << 31, 1u << 31)) { /* AHBIDL */
        return 0;
    }
    OTG(GUSBCFG) &= ~(1u << 6); /* PHYSEL = 0: the external ULPI PHY */
    OTG(GRSTCTL) = 1u;          /* CSRST */
    if (!wait_otg(GRSTCTL, 1u, 0u)) {
        return 0;
    }
    /* Forced device mode; turnaround 9 PHY clocks (RM0399: ULPI, HS). */
    OTG(GUSBCFG) = (OTG(GUSBCFG) & ~((0xFu << 10) | (1u << 29))) | (1u << 30) | (9u << 10);
    OTG(DCFG) = 0u; /* DSPD = 0: high speed, address 0 */
    OTG(GRXFSIZ) = 512u;                        /* words */
    OTG(DIEPTXF0) = (64u << 16) | 512u;         /* EP0 TX: 64 words after RX */
    OTG(DIEPTXF1) = (128u << 16) | 576u;        /* EP1 TX: 128 words */
    OTG(GRSTCTL) = (0x10u << 6) | (1u << 5);    /* flush every TX FIFO */
    (void)wait_otg(GRSTCTL, 1u << 5, 0u);
    OTG(GRSTCTL) = 1u << 4;                     /* flush RX FIFO */
    (void)wait_otg(GRSTCTL, 1u << 4, 0u);
    /* Interrupts: RX FIFO level, bus reset, enumeration done; the global
     * mask in GAHBCFG; the NVIC line at priority 8 of 16 (upper nibble). */
    OTG(GINTMSK) = GINT_RXFLVL | GINT_USBRST | GINT_ENUMDNE;
    OTG(GAHBCFG) = 1u; /* GINTMSK */
    TDC_REG32(TDC_CM_NVIC_IPR(TDC_STM32_OTG_HS_IRQN / 4u)) =
        (TDC_REG32(TDC_CM_NVIC_IPR(TDC_STM32_OTG_HS_IRQN / 4u)) & ~(0xFFu << (8u * (TDC_STM32_OTG_HS_IRQN % 4u)))) |
        (0x80u << (8u * (TDC_STM32_OTG_HS_IRQN % 4u)));
    TDC_REG32(TDC_CM_NVIC_ISER(OTG_IRQ_WORD)) = OTG_IRQ_BIT;
    OTG(DCTL) &= ~(1u << 1); /* SDIS = 0: connect */
    return 1;
}

static void ep0_arm_setup(void)
{
    OTG(DOEPTSIZ0) = (3u << 29) | (1u << 19) | 24u; /* STUPCNT 3, PKTCNT 1 */
    OTG(DOEPCTL0) |= EPENA | CNAK;
}

/* One packet of a control OUT data stage (7-bit transfer size field). */
static void ep0_arm_out(void)
{
    const uint32_t left = g_ctl_out_want - g_ctl_out_len;
    OTG(DOEPTSIZ0) = (1u << 19) | (left < 64u ? left : 64u);
    OTG(DOEPCTL0) |= EPENA | CNAK;
}

static void ep_write(uint32_t ep, uint32_t tsiz_off, uint32_t ctl_off, const uint8_t *p, uint32_t n, uint32_t mps)
{
    const uint32_t pkts = n == 0u ? 1u : (n + mps - 1u) / mps;
    OTG(tsiz_off) = (pkts << 19) | n;
    OTG(ctl_off) |= EPENA | CNAK;
    for (uint32_t i = 0; i < n; i += 4u) {
        uint32_t w = 0;
        for (uint32_t b = 0; b < 4u && i + b < n; b++) {
            w |= (uint32_t)p[i + b] << (8u * b);
        }
        FIFO(ep) = w;
    }
}

/* Endpoint 0's transfer size field holds 7 bits and its packet count 2
 * (RM0399 OTG_DIEPTSIZ0), so longer replies (a DFU upload block) go out one
 * 64-byte packet at a time, each after the previous one left (bounded
 * wait: the host polls IN at least every microframe while it reads). */
static void ep0_send(const uint8_t *p, uint32_t n)
{
    uint32_t off = 0;
    do {
        if (!wait_otg(DIEPCTL0, EPENA, 0u)) {
            return;
        }
        const uint32_t k = n - off < 64u ? n - off : 64u;
        ep_write(0u, DIEPTSIZ0, DIEPCTL0, p + off, k, 64u);
        off += k;
    } while (off < n);
}

static void ep0_stall(void)
{
    OTG(DIEPCTL0) |= STALL;
    OTG(DOEPCTL0) |= STALL;
}

static void status_in(void)
{
    uint8_t st[TDC_USB_STATUS_LEN];
    tdc_usbp_status_report(&g_proto, st);
    ep_write(1u, EP(DIEPTSIZ0, 1u), EP(DIEPCTL0, 1u), st, sizeof st, HS_MPS);
}

static uint32_t ring_room(void)
{
    return RING_BYTES - (g_head - g_tail);
}

static void bulk_out_arm(void)
{
    OTG(EP(DOEPTSIZ0, 1u)) = (1u << 19) | HS_MPS;
    OTG(EP(DOEPCTL0, 1u)) |= EPENA | CNAK;
}

static void configure(void)
{
    OTG(EP(DOEPCTL0, 1u)) = USBAEP | BULK | SD0PID | HS_MPS;
    OTG(EP(DIEPCTL0, 1u)) = USBAEP | BULK | SD0PID | (1u << 22) | HS_MPS; /* TX FIFO 1 */
    g_configured = 1;
    bulk_out_arm();
    status_in();
}

/* One control request once its data stage (if OUT) is in. */
static void control(void)
{
    tdc_usbp_setup_t su;
    tdc_usbp_parse_setup(g_setup, &su);
    const int dir_in = (su.bm_request_type & 0x80u) != 0u;
    if ((su.bm_request_type & 0x7Fu) == 0u && su.b_request == 0x05u) { /* SET_ADDRESS */
        OTG(DCFG) = (OTG(DCFG) & ~(0x7Fu << 4)) | ((su.w_value & 0x7Fu) << 4);
        ep0_send(0, 0u);
        return;
    }
    if ((su.bm_request_type & 0x7Fu) == 0u && su.b_request == 0x09u) { /* SET_CONFIGURATION */
        if (su.w_value == 1u) {
            configure();
        }
        ep0_send(0, 0u);
        return;
    }
    uint32_t len = 0;
    if (tdc_usbp_control(&g_proto, &su, dir_in ? 0 : g_ctl, g_ctl, sizeof g_ctl, &len) != TDC_OK) {
        ep0_stall();
        return;
    }
    if (tdc_usbp_take_reset(&g_proto)) {
        ep0_send(0, 0u);
        TDC_REG32(TDC_CM_SCB_AIRCR) = (0x5FAu << 16) | (1u << 2);
    }
    ep0_send(g_ctl, dir_in ? len : 0u); /* IN data, or the OUT request's status stage */
}

/* Pops one received-status entry and its data; returns 0 when the RX FIFO
 * is empty. */
static int rx_pop(void)
{
    /* Words as the FIFO gives them: on this little-endian core their bytes
     * are the packet's bytes in order (read through an unsigned char
     * pointer, which may alias anything). */
    static uint32_t pkt32[HS_MPS / 4u];
    const uint8_t *const pkt = (const uint8_t *)pkt32;
    if (!(OTG(GINTSTS) & GINT_RXFLVL)) {
        return 0;
    }
    const uint32_t st = OTG(GRXSTSP);
    const uint32_t ep = st & 0xFu, bcnt = (st >> 4) & 0x7FFu, kind = (st >> 17) & 0xFu;
    const uint32_t words = (bcnt + 3u) / 4u;
    for (uint32_t i = 0; i < words; i++) {
        const uint32_t w = FIFO(0u); /* every OUT endpoint pops through FIFO 0's window */
        if (i < HS_MPS / 4u) {
            pkt32[i] = w;
        }
    }
    const uint32_t n = bcnt < HS_MPS ? bcnt : HS_MPS;
    if (kind == 6u && n >= 8u) { /* SETUP data */
        memcpy(g_setup, pkt, 8u);
    } else if (kind == 2u && ep == 0u) { /* control OUT data stage */
        const uint32_t room = (uint32_t)sizeof g_ctl - g_ctl_out_len;
        const uint32_t k = n < room ? n : room;
        memcpy(g_ctl + g_ctl_out_len, pkt, k);
        g_ctl_out_len += k;
    } else if (kind == 2u && ep == 1u) { /* link bytes */
        tdc_usbp_bulk_out(&g_proto, pkt, n);
        /* Armed only with room for a whole packet (below): n fits. */
        const uint32_t head = g_head, at = head % RING_BYTES;
        const uint32_t k = n < RING_BYTES - at ? n : RING_BYTES - at;
        memcpy(g_ring + at, pkt, k);
        memcpy(g_ring, pkt + k, n - k);
        __asm__ volatile("" ::: "memory"); /* the bytes before the new head */
        g_head = head + n;
    } else if (kind == 4u) { /* SETUP stage done */
        const uint32_t wlen = (uint32_t)g_setup[6] | ((uint32_t)g_setup[7] << 8);
        if (!(g_setup[0] & 0x80u) && wlen > sizeof g_ctl) {
            ep0_stall(); /* larger than any request of the protocol */
            ep0_arm_setup();
        } else if (!(g_setup[0] & 0x80u) && wlen > 0u) {
            g_ctl_out_len = 0u;
            g_ctl_out_want = wlen;
            ep0_arm_out();
        } else {
            control();
            ep0_arm_setup();
        }
    } else if (kind == 3u && ep == 0u && g_ctl_out_want) {
        if (g_ctl_out_len < g_ctl_out_want) {
            ep0_arm_out(); /* next packet of the data stage */
        } else {
            g_ctl_out_want = 0u;
            control();
            ep0_arm_setup();
        }
    } else if (kind == 3u && ep == 1u) {
        if (ring_room() >= HS_MPS) {
            bulk_out_arm();
        } else {
            g_out_parked = 1; /* the frame loop re-arms after reading */
        }
    }
    return 1;
}

void tdc_disco_usb_irq(void)
{
    const uint32_t gint = OTG(GINTSTS);
    if (gint & GINT_USBRST) {
        OTG(GINTSTS) = GINT_USBRST;
        OTG(DCFG) &= ~(0x7Fu << 4);
        g_configured = 0;
        if (tdc_usbp_bus_reset(&g_proto)) {
            /* A manifested download waits in the other bank: boot it
             * (option-byte bank swap, then reset; flash.c). */
            (void)tdc_disco_flash_activate_other_bank();
        }
        ep0_arm_setup();
    }
    if (gint & GINT_ENUMDNE) {
        OTG(GINTSTS) = GINT_ENUMDNE;
        OTG(DIEPCTL0) &= ~3u; /* MPSIZ 64 bytes */
        OTG(DCTL) |= 1u << 8;  /* CGINAK */
    }
    /* RXFLVL clears itself once the FIFO is empty; bounded per entry. */
    for (uint32_t i = 0; i < 64u && rx_pop(); i++) {
    }
}

void tdc_disco_usb_poll(void)
{
    TDC_REG32(TDC_CM_NVIC_ICER(OTG_IRQ_WORD)) = OTG_IRQ_BIT;
    __asm__ volatile("dsb\n\tisb" ::: "memory"); /* masked from the next instruction on */
    /* A DFU block answered dfuDNBUSY: erase and program it now, while the
     * host waits out bwPollTimeout (EP0 NAKs meanwhile). */
    (void)tdc_usbp_dfu_work(&g_proto);
    if (g_configured && (OTG(EP(DIEPINT0, 1u)) & 1u)) { /* XFRC: the host took the last report */
        OTG(EP(DIEPINT0, 1u)) = 1u;
        status_in();
    }
    if (g_out_parked && ring_room() >= HS_MPS) {
        g_out_parked = 0;
        bulk_out_arm();
    }
    TDC_REG32(TDC_CM_NVIC_ISER(OTG_IRQ_WORD)) = OTG_IRQ_BIT;
}

uint32_t tdc_disco_usb_read(uint8_t *buf, uint32_t cap)
{
    const uint32_t head = g_head;
    __asm__ volatile("" ::: "memory"); /* the bytes after the head that covers them */
    const uint32_t tail = g_tail, at = tail % RING_BYTES;
    const uint32_t n = head - tail < cap ? head - tail : cap;
    const uint32_t k = n < RING_BYTES - at ? n : RING_BYTES - at;
    memcpy(buf, g_ring + at, k);
    memcpy(buf + k, g_ring, n - k);
    __asm__ volatile("" ::: "memory"); /* copied out before the slots are given back */
    g_tail = tail + n;
    tdc_disco_usb_poll(); /* re-arms bulk OUT if the ring had filled */
    return n;
}
