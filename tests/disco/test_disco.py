#!/usr/bin/python3
"""test_disco.py - the STM32H747I-DISCO's board code, executed.

Runs the linked firmware ELF (make BOARD=stm32h747i-disco PANEL=disco-dsi)
on an emulated Cortex-M7 against the register models of disco_models.py
(every access outside the register map, with a clock off, or against an
RM0399 order rule stops the run), then checks the recorded register values
against values this file computes from RM0399's formulas and the parts'
data sheets.  Usage: test_disco.py ELF [unittest args]
"""
import math
import os
import re
import struct
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from disco_emu import Disco  # noqa: E402
from disco_models import EmuError, VOS_LIMITS_MHZ, FLASH_WS, ahb_div, apb_div  # noqa: E402

ELF = None
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
HSE_HZ = 25000000  # UM2411: 25 MHz crystal
SUPPLY_VOS_MAX = 1  # direct SMPS: VOS1 is the highest scale (VOS0 needs the LDO, DS12930)

# IS42S32800J data sheet, -6 speed grade (ns, or clocks where it gives clocks).
SDRAM_NS = {"tXSR": 70, "tRAS": 42, "tRC": 60, "tRP": 18, "tRCD": 18}
SDRAM_CLK = {"tMRD": 2, "tWR": 2}
SDRAM_REFRESH = (64e-3, 4096)  # 4096 refresh cycles every 64 ms
SDRAM_GEOMETRY = {"cols": 9, "rows": 12, "bits": 32, "banks": 4}

_BOOTED = None


def booted():
    """One board run to the frame loop's first transport read, shared by the
    read-only tests (2-3 s)."""
    global _BOOTED
    if _BOOTED is None:
        b = Disco(ELF)
        b.run_reset()
        _BOOTED = b
    return _BOOTED


def board_h_macros():
    with open(os.path.join(ROOT, "boards", "stm32h747i-disco", "board.h")) as f:
        text = f.read()
    macros = {k: re.sub(r"/\*.*", "", v).strip() for k, v in re.findall(r"#define (TDC_\w+) (.+)$", text, re.M)}
    def ev(name):
        expr = macros[name]
        expr = re.sub(r"\b(\d+)u\b", r"\1", expr)
        expr = re.sub(r"\b(TDC_\w+)\b", lambda m: str(ev(m.group(1))), expr)
        return eval(expr.replace("/", "//"), {})
    return ev


# The MB1166 panel's register tables in the controllers' data-sheet
# notation: "register  parameters" per line ("00*10" = ten 00h), "wait N"
# = N ms before the next command.  OTM8009A (Orise Tech data sheet,
# command set 2): a four-digit register is the command-2 address (C480h =
# register C4h at offset 80h).  NT35510 (Novatek data sheet): manufacturer
# command set, page 1 then page 0 (F0h selects the page).  The values are
# the MB1166 figures of ST's DISCO board support (otm8009a.c, nt35510.c),
# the OTM8009A gamma inside command set 2 as the data sheet and Linux's
# panel-orisetech-otm8009a.c have it; held here independently of
# boards/stm32h747i-disco/panel_tables.c, which must send the same bytes.
OTM8009A = """
FF00 80 09 01          # CMD2 enable 1
FF80 80 09             # CMD2 enable 2 (Orise)
C480 30                # SD_PCH_CTRL
wait 10
C48A 40                # not documented
wait 10
C5B1 A9                # PWR_CTRL4 +1
C591 34                # PWR_CTRL2 +1
C0B4 50                # P_DRV_M
D900 4E                # VCOMDC
C181 66                # OSC_ADJ 65 Hz
C1A1 08                # RGB_VID_SET
C592 01                # PWR_CTRL2 +2
C595 34                # PWR_CTRL2 +5
D800 79 79             # GVDDSET
C594 33                # PWR_CTRL2 +4
C0A3 1B                # SD_CTRL +1
C582 83                # PWR_CTRL1 +2
C481 83                # SD_PCH_CTRL +1
C1A1 0E                # RGB_VID_SET
B3A6 00 01             # PANSET
CE80 85 01 00 84 01 00 # GOAVST
CEA0 18 04 03 39 00 00 00 18 03 03 3A 00 00 00  # GOACLKA1
CEB0 18 02 03 3B 00 00 00 18 01 03 3C 00 00 00  # GOACLKA3
CFC0 01 01 20 20 00 00 01 02 00 00              # GOAECLK
CFD0 00
CB80 00*10             # PANCTRLSET1
CB90 00*15
CBA0 00*15
CBB0 00*10
CBC0 00 04 04 04 04 04 00*9
CBD0 00*6 04 04 04 04 04 00*4
CBE0 00*10
CBF0 FF*10             # PANCTRLSET8
CC80 00 26 09 0B 01 25 00*4                     # PANU2D1
CC90 00*11 26 0A 0C 02
CCA0 25 00*14
CCB0 00 25 0C 0A 02 26 00*4                     # PAND2U1
CCC0 00*11 25 0B 09 01
CCD0 26 00*14
C581 66                # PWR_CTRL1 +1
F5B6 06                # not documented
C6B1 06                # PWM_PARA3
E100 00 09 0F 0E 07 10 0B 0A 04 07 0B 08 0F 10 0A 01  # GMCT2.2P
E200 00 09 0F 0E 07 10 0B 0A 04 07 0B 08 0F 10 0A 01  # GMCT2.2N
FF00 FF FF FF          # leave command 2
00                     # nop
"""
NT35510 = """
F0 55 AA 52 08 01      # MAUCCTR page 1
B0 03 03 03            # SETAVDD
B6 46 46 46            # BT1CTR
B1 03 03 03            # SETAVEE
B7 36 36 36            # BT2CTR
B2 00 00 02            # SETVCL
B8 26 26 26            # BT3CTR
BF 01                  # VGHCTR
B3 09 09 09            # SETVGH
B9 36 36 36            # BT4CTR
B5 08 08 08            # SETVGL
BA 26 26 26            # BT5CTR
BC 00 80 00            # SETVGP
BD 00 80 00            # SETVGN
BE 00 50               # SETVCMOFF
F0 55 AA 52 08 00      # MAUCCTR page 0
B1 FC 00               # DOPCTR
B6 03                  # SDHDTCTR
B5 50                  # DPRSLCTR
B7 00 00               # GSEQCTR
B8 01 02 02 02         # SDEQCTR
BC 00 00 00            # INVCTR
CC 03 00 00
BA 01                  # SDVPCTR
wait 200
"""


def panel_table(text):
    """[(register, parameter bytes, wait ms after)] from the notation above."""
    rows = []
    for line in text.splitlines():
        f = line.split("#")[0].split()
        if not f:
            continue
        if f[0] == "wait":
            reg, params, _w = rows[-1]
            rows[-1] = (reg, params, int(f[1]))
            continue
        params = bytearray()
        for tok in f[1:]:
            v, _, n = tok.partition("*")
            params += bytes([int(v, 16)]) * int(n or 1)
        rows.append((int(f[0], 16), bytes(params), 0))
    return rows



class Clocks(unittest.TestCase):
    def test_supply_written_once_smps(self):
        b = booted()
        w = b.writes("PWR", "CR3")
        self.assertEqual(len(w), 1, "PWR_CR3 supply configuration is write-once")
        self.assertEqual(w[0].value & 0x3F, 0x4, "direct SMPS: SDEN = 1, LDOEN = 0, BYPASS = 0")
        i_cr3 = b.log.index(w[0])
        i_rdy = b.index(lambda a: a.reg == "CSR1" and a.value >> 13 & 1)
        i_vos = b.index(lambda a: a.op == "W" and a.reg == "D3CR")
        self.assertTrue(i_cr3 < i_rdy < i_vos, "CR3, then ACTVOSRDY read, then VOS")

    def test_vos_and_clock_limits(self):
        b = booted()
        self.assertEqual(b.pwr.vos(), SUPPLY_VOS_MAX)
        self.assertTrue(b.rcc.switches, "SYSCLK never switched")
        for sysclk, vos in b.rcc.switches:
            self.assertEqual(vos, SUPPLY_VOS_MAX)
            self.assertLessEqual(sysclk, VOS_LIMITS_MHZ[vos][0] * 1000000)
        i_vosrdy = b.index(lambda a: a.reg == "D3CR" and a.op == "R" and a.value >> 13 & 1)
        i_sw = b.index(lambda a: a.op == "W" and a.reg == "CFGR")
        self.assertTrue(0 <= i_vosrdy < i_sw, "VOSRDY read before the switch to PLL1")

    def test_pll1_from_formula(self):
        b = booted()
        sel, cfg, divr = b.last("RCC", "PLLCKSELR"), b.last("RCC", "PLLCFGR"), b.last("RCC", "PLL1DIVR")
        self.assertEqual(sel & 3, 2, "PLL source HSE")
        divm = sel >> 4 & 0x3F
        n, p, q, r = (divr & 0x1FF) + 1, (divr >> 9 & 0x7F) + 1, (divr >> 16 & 0x7F) + 1, (divr >> 24 & 0x7F) + 1
        ref = HSE_HZ / divm  # RM0399 RCC: ref1_ck = HSE / DIVM1
        vco = ref * n  # integer mode: VCO = ref1_ck x DIVN1
        rge = cfg >> 2 & 3
        lo, hi = [(1e6, 2e6), (2e6, 4e6), (4e6, 8e6), (8e6, 16e6)][rge]
        self.assertTrue(lo <= ref <= hi, "PLL1RGE %d does not hold %g Hz" % (rge, ref))
        self.assertEqual(cfg >> 1 & 1, 0, "wide VCO for a 2-16 MHz input")
        self.assertTrue(192e6 <= vco <= 960e6)
        self.assertEqual(p % 2, 0, "DIVP1 even")
        sysclk = vco / p
        self.assertEqual(sysclk, VOS_LIMITS_MHZ[SUPPLY_VOS_MAX][0] * 1e6, "400 MHz: the VOS1 maximum")
        self.assertLessEqual(vco / q, 200e6)
        self.assertLessEqual(vco / r, 400e6)
        ev = board_h_macros()
        self.assertEqual(ev("TDC_BOARD_CPU_HZ"), sysclk, "board.h timer constant = the programmed clock")
        d1, d2, d3 = b.last("RCC", "D1CFGR"), b.last("RCC", "D2CFGR"), b.last("RCC", "D3CFGR")
        cpu = sysclk / ahb_div(d1 >> 8 & 0xF)
        hclk = cpu / ahb_div(d1 & 0xF)
        self.assertEqual(cpu, sysclk)
        self.assertEqual(hclk, 200e6)
        for pre in (d1 >> 4 & 7, d2 >> 4 & 7, d2 >> 8 & 7, d3 >> 4 & 7):
            self.assertEqual(hclk / apb_div(pre), 100e6)
        self.assertEqual(ev("TDC_DISCO_HCLK_HZ"), hclk)
        self.assertEqual(ev("TDC_DISCO_PCLK_HZ"), 100e6)

    def test_flash_wait_states(self):
        b = booted()
        acr = b.last("FLASH", "ACR")
        want = next((lat, wrh) for fmax, lat, wrh in FLASH_WS[SUPPLY_VOS_MAX] if 200 <= fmax)
        self.assertEqual((acr & 0xF, acr >> 4 & 3), want)
        i_acr = b.index(lambda a: a.op == "W" and a.reg == "ACR")
        i_rb = b.index(lambda a: a.op == "R" and a.reg == "ACR" and a.value == acr)
        i_sw = b.index(lambda a: a.op == "W" and a.reg == "CFGR")
        self.assertTrue(i_acr < i_rb < i_sw, "ACR written and read back before the switch")

    def test_ldo_wired_board_refused(self):
        # The same image on a board whose VCORE came from the LDO would
        # wait for ACTVOSRDY forever: the model says so.
        b = Disco(ELF, supply="ldo")
        with self.assertRaisesRegex(EmuError, "PWR_CR3"):
            b.run_reset()


class Sdram(unittest.TestCase):
    def test_geometry_and_timings_from_ns(self):
        b = booted()
        sdcr1, sdcr2 = b.last("FMC", "SDCR1"), b.last("FMC", "SDCR2")
        hclk3 = b.rcc.clocks()["hclk"]
        sdclk = hclk3 / (sdcr1 >> 10 & 3)  # SDCLK field: 2 = HCLK/2, 3 = HCLK/3
        self.assertLessEqual(sdclk, 166e6, "-6 grade: 166 MHz")
        for cr in (sdcr2,):
            self.assertEqual((cr & 3) + 8, SDRAM_GEOMETRY["cols"])
            self.assertEqual((cr >> 2 & 3) + 11, SDRAM_GEOMETRY["rows"])
            self.assertEqual(8 << (cr >> 4 & 3), SDRAM_GEOMETRY["bits"])
            self.assertEqual(2 << (cr >> 6 & 1), SDRAM_GEOMETRY["banks"])
        cas = sdcr2 >> 7 & 3
        cyc = {k: math.ceil(ns * 1e-9 * sdclk - 1e-9) for k, ns in SDRAM_NS.items()}
        cyc.update(SDRAM_CLK)
        # RM0399 FMC_SDTRx: TWR >= TRAS - TRCD and TWR >= TRC - TRCD - TRP.
        cyc["tWR"] = max(cyc["tWR"], cyc["tRAS"] - cyc["tRCD"], cyc["tRC"] - cyc["tRCD"] - cyc["tRP"])
        sdtr1, sdtr2 = b.last("FMC", "SDTR1"), b.last("FMC", "SDTR2")
        fields = {"tMRD": 0, "tXSR": 4, "tRAS": 8, "tRC": 12, "tWR": 16, "tRP": 20, "tRCD": 24}
        for name, sh in fields.items():
            # TRC and TRP of both banks come from SDTR1 (RM0399 FMC_SDTRx).
            reg = sdtr1 if name in ("tRC", "tRP") else sdtr2
            self.assertEqual((reg >> sh & 0xF) + 1, cyc[name], "%s: %d cycles at %g MHz" % (name, cyc[name], sdclk / 1e6))
        period, rows = SDRAM_REFRESH
        count = math.floor(period / rows * sdclk) - 20  # RM0399 FMC_SDRTR: COUNT = refresh rate x SDCLK - 20
        self.assertEqual(b.last("FMC", "SDRTR") >> 1 & 0x1FFF, count)
        modes = [c for c in b.fmc.commands]
        self.assertEqual([c[0] for c in modes], [1, 2, 3, 4])
        mrd = modes[3][2]
        self.assertEqual(mrd >> 4 & 7, cas, "mode register CAS = SDCR CAS")
        self.assertEqual(mrd & 7, 0, "burst length 1")
        self.assertGreaterEqual(modes[2][1], 2, "at least 2 auto-refresh cycles")
        # >= 100 us between clock enable and precharge-all: the M7 retires at
        # most 2 instructions a cycle, so >= 2 x 100 us x CPU clock instructions.
        self.assertGreaterEqual(modes[1][3], 2 * 100e-6 * b.rcc.clocks()["cpu"])

    def test_sdram_used_only_after_init(self):
        b = booted()
        self.assertTrue(b.sdram_mapped, "crt0 zeroed the SDRAM buffers after the FMC sequence")


class Caches(unittest.TestCase):
    def test_mpu_region_and_dcache(self):
        b = booted()
        s = b.scs
        self.assertTrue(s.dcache_on() and s.v[0xED14] >> 17 & 1)
        rn, rasr = s.mpu_attr(0xD0000000)
        self.assertEqual(1 << ((rasr >> 1 & 0x1F) + 1), 32 << 20)
        self.assertEqual((rasr >> 19 & 7, rasr >> 17 & 1, rasr >> 16 & 1), (1, 1, 1), "Normal WBWA")
        self.assertEqual(rasr >> 28 & 1, 1, "execute never")
        i_mpu = b.index(lambda a: a.op == "W" and a.reg == "MPU_CTRL")
        i_dc = b.index(lambda a: a.op == "W" and a.reg == "CCR" and a.value >> 16 & 1)
        i_ext = b.index(lambda a: a.reg == "SDRTR")
        self.assertTrue(i_ext < i_mpu < i_dc)

    def test_flip_cleans_frame_buffer(self):
        b = Disco(ELF)
        b.run_reset()
        fb = 0xD0100000
        w, h, stride = 800, 480, 800 * 3
        # The model refuses a flip whose frame-buffer lines were not all
        # cleaned (DCCMVAC) since the previous one while the D-cache is on.
        rc = b.call("tdc_board_panel_show", fb, stride, w, h, 0)
        self.assertEqual(rc, 0, "TDC_BOARD_OK")
        self.assertEqual(b.ltdc.flips, [(fb, (stride << 16) | (w * 3 + 7), h)])
        # A frame larger than the DISCO's panel is cropped to it.
        b.call("tdc_board_panel_show", fb, 2160 * 3, 2160, 1200, 1)
        self.assertEqual(b.ltdc.flips[1], (fb, ((2160 * 3) << 16) | (w * 3 + 7), h))


def panel_profile(name):
    out = {}
    with open(os.path.join(ROOT, "boards", "panels", name + ".panel")) as fh:
        for line in fh:
            f = line.split()
            if f and not f[0].startswith("#"):
                out[f[0]] = f[1:]
    return out


class Ltdc(unittest.TestCase):
    # OTM8009A data sheet video-mode timing (also what ST's DISCO set-up
    # uses for the NT35510 revision): sync, back porch, front porch.
    H = (2, 34, 34)
    V = (1, 15, 16)

    def test_timings_from_panel(self):
        b = booted()
        p = panel_profile("disco-dsi")
        w, h, hz = int(p["width"][0]), int(p["height"][0]), int(p["refresh_hz"][0])
        (hs, hbp, hfp), (vs, vbp, vfp) = self.H, self.V
        want = {"SSCR": ((hs - 1) << 16) | (vs - 1),
                "BPCR": ((hs + hbp - 1) << 16) | (vs + vbp - 1),
                "AWCR": ((hs + hbp + w - 1) << 16) | (vs + vbp + h - 1),
                "TWCR": ((hs + hbp + w + hfp - 1) << 16) | (vs + vbp + h + vfp - 1)}
        for reg, v in want.items():
            self.assertEqual(b.last("LTDC", reg), v, reg)
        self.assertEqual(b.last("LTDC", "L1WHPCR"), ((hs + hbp + w - 1) << 16) | (hs + hbp))
        self.assertEqual(b.last("LTDC", "L1WVPCR"), ((vs + vbp + h - 1) << 16) | (vs + vbp))
        self.assertEqual(b.last("LTDC", "L1PFCR"), 1, "RGB888")
        self.assertEqual(b.ltdc.v[0x18] & 1, 1, "LTDC enabled")
        self.assertEqual(b.ltdc.v[0x84] & 1, 0, "layer off until the first frame")
        # Pixel clock = PLL3R = HSE / DIVM3 x DIVN3 / DIVR3 (RM0399 RCC).
        sel, divr = b.last("RCC", "PLLCKSELR"), b.last("RCC", "PLL3DIVR")
        pclk = HSE_HZ / (sel >> 20 & 0x3F) * ((divr & 0x1FF) + 1) / ((divr >> 24 & 0x7F) + 1)
        total = (hs + hbp + w + hfp) * (vs + vbp + h + vfp)
        self.assertLess(abs(pclk / total - hz) / hz, 0.005, "frame rate %.3f Hz" % (pclk / total))
        self.assertEqual(b.rcc.pll(3)[4], int(pclk))


class DsiPanel(unittest.TestCase):
    LANES = 2

    def test_pll_and_video_timings(self):
        b = booted()
        w = b.last("DSI", "WRPCR")
        ndiv, idf, odf = w >> 2 & 0x7F, w >> 11 & 0xF, 1 << (w >> 16 & 3)
        lane = HSE_HZ * ndiv / (idf * odf)  # RM0399 DSI wrapper PLL
        self.assertTrue(500e6 <= 2 * lane * odf <= 1000e6, "VCO range")
        self.assertLessEqual(lane, 500e6, "D-PHY lane rate")
        sel, d3 = b.last("RCC", "PLLCKSELR"), b.last("RCC", "PLL3DIVR")
        pclk = HSE_HZ / (sel >> 20 & 0x3F) * ((d3 & 0x1FF) + 1) / ((d3 >> 24 & 0x7F) + 1)
        self.assertGreaterEqual(self.LANES * lane, 24 * pclk, "2 lanes carry RGB888 at the pixel clock")
        self.assertEqual(b.last("DSI", "PCONFR") & 3, self.LANES - 1)
        self.assertEqual(b.last("DSI", "WPCR0") & 0x3F, round(4e9 / lane), "UIX4: 4 x unit interval in ns")
        self.assertLessEqual(lane / 8 / (b.last("DSI", "CCR") & 0xFF), 20e6, "escape clock <= 20 MHz")
        p = panel_profile("disco-dsi")
        w_px, h_px = int(p["width"][0]), int(p["height"][0])
        (hs, hbp, hfp), (vs, vbp, vfp) = Ltdc.H, Ltdc.V
        lbc = lane / 8  # lane byte clock
        for reg, px in (("VHSACR", hs), ("VHBPCR", hbp), ("VLCR", hs + hbp + w_px + hfp)):
            self.assertEqual(b.last("DSI", reg), math.floor(px * lbc / pclk), reg)
        for reg, lines in (("VVSACR", vs), ("VVBPCR", vbp), ("VVFPCR", vfp), ("VVACR", h_px)):
            self.assertEqual(b.last("DSI", reg), lines, reg)
        self.assertEqual(b.last("DSI", "VPCR"), w_px)
        self.assertEqual((b.last("DSI", "LCOLCR") & 0xF, b.last("DSI", "WCFGR") >> 1 & 7), (5, 5), "24-bit colour")
        self.assertEqual(b.last("DSI", "WCFGR") & 1, 0, "video mode")
        # DSI started after the LTDC (the model enforces it; here the order is visible).
        i_ltdc = b.index(lambda a: a.reg == "GCR" and a.op == "W" and a.value & 1)
        i_dsi = b.index(lambda a: a.reg == "WCR" and a.op == "W" and a.value >> 3 & 1)
        self.assertTrue(0 <= i_ltdc < i_dsi)

    def expected_dcs(self):
        """The MIPI DCS 1.1 start-up for a landscape RGB888 panel of the
        profile's size (command codes and parameter layouts of DCS:
        exit_sleep_mode 0x11 then 120 ms, set_pixel_format 0x3A (0x77: 24
        bit), set_address_mode 0x36 (MV|MX), set_column_address 0x2A /
        set_page_address 0x2B (start, end, 16-bit big-endian), set_tear_on
        0x35, write brightness 0x51, write CTRL display 0x53, write CABC 0x55
        (off), set_display_on 0x29, write_memory_start 0x2C)."""
        p = panel_profile("disco-dsi")
        w, h = int(p["width"][0]), int(p["height"][0])
        return [(0x11, b"", 120), (0x3A, b"\x77", 0), (0x36, b"\x60", 0),
                (0x2A, bytes([0, 0, (w - 1) >> 8, (w - 1) & 0xFF]), 0),
                (0x2B, bytes([0, 0, (h - 1) >> 8, (h - 1) & 0xFF]), 0),
                (0x35, b"\x00", 0), (0x51, b"\xff", 0), (0x53, b"\x2c", 0), (0x55, b"\x00", 0),
                (0x29, b"", 0), (0x2C, b"", 0)]

    @staticmethod
    def packets(rows):
        """Rows (register, parameters, wait ms) -> the DSI packets they
        are, [(data type, bytes, wait ms after)]: a register above 0xFF is an
        OTM8009A command-2 address, sent as the address shift (DCS 00h with
        its low byte) and then its high byte; DCS short write without
        (0x05) or with one parameter (0x15), long write (0x39) beyond."""
        out = []
        for reg, params, wait in rows:
            if reg > 0xFF:
                out.append((0x15, bytes([0x00, reg & 0xFF]), 0))
                reg >>= 8
            dt = 0x05 if not params else 0x15 if len(params) == 1 else 0x39
            out.append((dt, bytes([reg]) + params, wait))
        return out

    def check_panel(self, b, ids, name, table):
        writes = [(dt, d) for dt, d, _c in b.dsi.packets if dt != 0x06]
        reads = [d[0] for dt, d, _c in b.dsi.packets if dt == 0x06]
        self.assertEqual(reads, ids)
        want = self.packets(table + self.expected_dcs())
        for i, (got, (dt, data, _w)) in enumerate(zip(writes, want)):
            self.assertEqual(got, (dt, data), "packet %d of %d" % (i, len(want)))
        self.assertEqual(len(writes), len(want), "packet count")
        # Each wait the data sheets ask for, measured on the model's clock
        # (DWT cycles) from that packet to the next.
        cyc = [c for dt, _d, c in b.dsi.packets if dt != 0x06]
        ms_per_cyc = 1000.0 / b.rcc.clocks()["cpu"]
        for i, (_dt, data, wait) in enumerate(want[:-1]):
            if wait:
                self.assertGreaterEqual((cyc[i + 1] - cyc[i]) * ms_per_cyc, wait,
                                        "%d ms after packet %d (%s)" % (wait, i, data.hex()))
        self.assertIn("panel controller %s" % name, b.uart_text())
        gj, gg = b.gpio[9], b.gpio[6]
        self.assertEqual((gj.mode(12), gj.out(12), gg.mode(3), gg.out(3)), (1, 1, 1, 1), "backlight on, reset released")

    def test_otm8009a(self):
        self.check_panel(booted(), [0xDA], "OTM8009A", panel_table(OTM8009A))

    def test_nt35510(self):
        b = Disco(ELF, panel="nt35510")
        b.run_reset()
        self.check_panel(b, [0xDA, 0xDB], "NT35510", panel_table(NT35510))

    def test_unknown_controller(self):
        # Neither ID: the DCS start-up only, and a log line naming ID1.
        b = Disco(ELF, panel="unknown")
        b.run_reset()
        writes = [(dt, d) for dt, d, _c in b.dsi.packets if dt != 0x06]
        self.assertEqual(writes, [(dt, d) for dt, d, _w in self.packets(self.expected_dcs())])
        self.assertIn("unknown panel controller, ID1 0x00000000", b.uart_text())


class FlashUpdate(unittest.TestCase):
    MIB = 1 << 20
    SRC = 0x24020000  # staging in AXI SRAM, clear of .data/.bss and the stack
    BLOCK = 4096      # a DFU download block

    def image(self, n=300010, seed=7):
        x, out = seed, bytearray()
        for _ in range(n):
            x = (x * 1103515245 + 12345) & 0x7FFFFFFF
            out.append(x >> 16 & 0xFF)
        return bytes(out)

    def download(self, b, img):
        b.uc.mem_write(self.SRC, img)
        for off in range(0, len(img), self.BLOCK):
            n = min(self.BLOCK, len(img) - off)
            rc = b.call("tdc_disco_flash_write", 0, self.MIB + off, self.SRC + off, n)
            if b.power_lost:
                return None
            if rc != 0:
                return rc
        return 0

    def running_bank(self, b):
        return bytes(b.uc.mem_read(0x08000000, self.MIB))

    def test_update_then_swap(self):
        self.update_then_swap(0)

    def test_update_then_swap_back(self):
        # Running from bank 2 (swapped): the update goes to bank 1 through
        # register set 1, and the swap returns.
        self.update_then_swap(1)

    def update_then_swap(self, swapped):
        b = Disco(ELF)
        b.flash.v[0x1C] |= swapped << 31
        b.run_reset()
        before = self.running_bank(b)
        img = self.image()
        self.assertEqual(self.download(b, img), 0)
        bank2 = bytes(b.uc.mem_read(0x08100000, self.MIB))
        pad = (-len(img)) % 32
        self.assertEqual(bank2[:len(img) + pad], img + b"\xff" * pad, "image + erased tail of its last flash word")
        self.assertEqual(sorted(b.flash.erased), [(0 if swapped else 0x100, s) for s in range(math.ceil(len(img) / (128 << 10)))],
                         "each 128 KiB sector the image covers erased once")
        self.assertEqual(len(b.flash.programmed), math.ceil(len(img) / 32), "one program per 256-bit word")
        self.assertEqual(self.running_bank(b), before, "running bank untouched")
        b.uc.mem_write(self.SRC, b"\0" * 64)
        self.assertEqual(b.call("tdc_disco_flash_read", 0, self.MIB + 4096, self.SRC, 64), 0)
        self.assertEqual(bytes(b.uc.mem_read(self.SRC, 64)), img[4096:4160])
        swap0 = b.flash.v[0x1C] >> 31
        b.call("tdc_disco_flash_activate_other_bank")
        self.assertEqual(b.flash.v[0x1C] >> 31, swap0 ^ 1, "SWAP_BANK toggled")
        self.assertTrue(b.scs.reset_requested, "reset to boot the other bank")

    def test_running_bank_refused(self):
        b = Disco(ELF)
        b.run_reset()
        n = len(b.log)
        b.uc.mem_write(self.SRC, b"\0" * 64)
        self.assertNotEqual(b.call("tdc_disco_flash_write", 0, 0, self.SRC, 64), 0)
        self.assertFalse([a for a in b.log[n:] if a.periph == "FLASH"], "no flash register touched")

    def test_power_loss_mid_update(self):
        img = self.image()
        for cut in (1, 2500):  # during the first sector erase; while programming the last sector
            b = Disco(ELF)
            b.run_reset()
            before = self.running_bank(b)
            b.flash.power_cut_at = b.flash.ops + cut
            self.assertIsNone(self.download(b, img), "power cut at operation %d" % cut)
            self.assertEqual(self.running_bank(b), before, "running bank intact after the cut")
            self.assertEqual(b.flash.v[0x1C] >> 31, 0, "banks not swapped")
            self.assertNotEqual(bytes(b.uc.mem_read(0x08100000, len(img))), img, "the other bank is incomplete")
            if cut != 1:
                continue
            # Power back: the same (intact) image boots.
            again = Disco(ELF)
            again.uc.mem_write(0x08100000, bytes(b.uc.mem_read(0x08100000, self.MIB)))
            again.run_reset()
            self.assertIn("power-on", again.uart_text())

    def test_erase_busy_times_out(self):
        b = Disco(ELF)
        b.run_reset()
        b.flash.stuck_busy = True
        b.scs.cyc_step = 4000000  # 10 ms of model time per DWT read
        t0 = b.scs.cyc
        b.uc.mem_write(self.SRC, b"\0" * 64)
        self.assertNotEqual(b.call("tdc_disco_flash_write", 0, self.MIB, self.SRC, 64), 0, "busy flash reported")
        waited_ms = (b.scs.cyc - t0) / (b.rcc.clocks()["cpu"] / 1000)
        ev = board_h_macros()
        self.assertGreaterEqual(waited_ms, ev("TDC_DISCO_FLASH_ERASE_MS"))
        self.assertLess(waited_ms, 2 * ev("TDC_DISCO_FLASH_ERASE_MS") + 100)
        self.assertEqual(b.flash.erased, [], "no erase started on a busy bank")


class UsbHs(unittest.TestCase):
    """A scripted host against the DWC2 model: enumeration through the
    project's protocol code on endpoint 0, then a bulk OUT transfer read
    back through tdc_board_transport_read().  Nothing polls the core: each
    host event asserts the model's interrupt line and the harness runs the
    handler the vector table names (disco_emu.Disco.interrupts).  (The
    host's zero-length status stages after IN data are not sent: the
    driver ignores them.)"""
    GOT = 0x24070000  # a word for transport_read's *got
    BUF = 0x24060000

    def control(self, b, bm, req, val, idx, length, data=b""):
        n0 = len(b.usb.sent[0])
        b.usb.setup(struct.pack("<BBHHH", bm, req, val, idx, length))
        for off in range(0, length if not bm & 0x80 else 0, 64):  # OUT data stage, 64-byte packets
            self.assertTrue(b.usb.out(0, data[off:off + 64]), "EP0 armed for each OUT data packet")
        sent = b.usb.sent[0][n0:]
        self.assertGreaterEqual(len(sent), 1, "an IN data or status stage")
        self.assertTrue(all(len(p) <= 64 for p in sent), "EP0 packets of at most 64 bytes")
        self.assertFalse(b.usb.v[0x900] >> 21 & 1, "not stalled")
        return b"".join(sent)

    def test_enumerate_and_bulk_out(self):
        b = Disco(ELF)
        b.run_reset()
        b.usb.bus_reset()
        dev = self.control(b, 0x80, 6, 0x0100, 0, 64)
        self.assertEqual((len(dev), dev[0], dev[1], dev[7]), (18, 18, 1, 64), "device descriptor, EP0 64 bytes")
        self.assertEqual(self.control(b, 0x00, 5, 7, 0, 0), b"", "SET_ADDRESS status")
        self.assertEqual(b.usb.v[0x800] >> 4 & 0x7F, 7, "DCFG.DAD")
        head = self.control(b, 0x80, 6, 0x0200, 0, 9)
        total = struct.unpack_from("<H", head, 2)[0]
        cfg = self.control(b, 0x80, 6, 0x0200, 0, total)
        eps = {cfg[i + 2]: struct.unpack_from("<H", cfg, i + 4)[0] for i in range(len(cfg) - 6)
               if cfg[i] == 7 and cfg[i + 1] == 5}
        self.assertEqual(eps.get(0x01), 512, "bulk OUT 0x01, 512 bytes at high speed")
        self.assertEqual(eps.get(0x81), 512, "bulk IN 0x81")
        self.assertEqual(self.control(b, 0x00, 9, 1, 0, 0), b"", "SET_CONFIGURATION status")
        self.assertGreaterEqual(b.irqs_taken, 6, "served by the OTG_HS interrupt")
        status = b.usb.sent[1][-1]
        self.assertEqual(struct.unpack_from("<I", status, 0)[0], 0x53434454, "status report on bulk IN ('TDCS')")
        info = self.control(b, 0xC1, 0x01, 0, 0, 64)
        self.assertIn(b"stm32h747i-disco", info, "BOARD_INFO names the board")
        # A bulk transfer of link-stream bytes, 512-byte packets.
        data = bytes((i * 37 + 11) & 0xFF for i in range(3000))
        for off in range(0, len(data), 512):
            self.assertTrue(b.usb.out(1, data[off:off + 512]), "bulk OUT re-armed after each packet")
        got = b""
        for _ in range(4):
            rc = b.call("tdc_board_transport_read", self.BUF, 4096, self.GOT)
            self.assertEqual(rc, 0, "TDC_BOARD_OK")
            n = struct.unpack("<I", bytes(b.uc.mem_read(self.GOT, 4)))[0]
            got += bytes(b.uc.mem_read(self.BUF, n))
        self.assertEqual(got, data)
        # While nothing reads (a stage runs), the interrupt fills the ring
        # until it has no room for a packet; then bulk OUT NAKs, and the
        # next transport_read re-arms it: flow control, nothing dropped.
        ring = board_h_macros()("TDC_DISCO_USB_RING_BYTES")
        pkts = [bytes([(k * 7 + i) & 0xFF for i in range(512)]) for k in range(ring // 512 + 3)]
        taken = 0
        while taken < len(pkts) and b.usb.out(1, pkts[taken]):
            taken += 1
        self.assertEqual(taken, ring // 512, "packets taken before the ring is full")
        stream = b""
        while len(stream) < len(pkts) * 512:
            b.call("tdc_board_transport_read", self.BUF, 4096, self.GOT)
            n = struct.unpack("<I", bytes(b.uc.mem_read(self.GOT, 4)))[0]
            self.assertGreater(n, 0, "ring drained")
            stream += bytes(b.uc.mem_read(self.BUF, n))
            while taken < len(pkts) and b.usb.out(1, pkts[taken]):
                taken += 1
        self.assertEqual(stream, b"".join(pkts), "every byte once, in order")
        self.dfu_block_through_ep0(b)

    def dfu_block_through_ep0(self, b):
        """A DFU download block (wTransferSize 1024) through EP0 into the
        flash driver, landing in the bank not running.  It starts a sector,
        whose erase (the model's erase_ms) cannot fit the DNLOAD request:
        GETSTATUS (answered in the interrupt) gives dfuDNBUSY with a
        bwPollTimeout covering the erase, the board writes after that reply
        in the frame loop's vsync wait, and the host's next
        GETSTATUS (sent after bwPollTimeout) finds dfuDNLOAD-IDLE."""
        block = bytes((i * 13 + 5) & 0xFF for i in range(1024))
        self.assertEqual(self.control(b, 0x21, 1, 0, 1, len(block), block), b"", "DFU_DNLOAD status stage")
        self.assertEqual(b.flash.erased, [], "no erase within the DNLOAD request")
        t0 = b.scs.cyc
        st = self.control(b, 0xA1, 3, 0, 1, 6)  # answered in the interrupt
        self.assertEqual(b.flash.erased, [], "no erase in the interrupt handler")
        b.call("tdc_board_vsync_wait")  # the frame loop's idle time does the DFU work
        busy_ms = (b.scs.cyc - t0) / (b.rcc.clocks()["cpu"] / 1000)
        poll_ms = st[1] | st[2] << 8 | st[3] << 16
        self.assertEqual((st[0], st[4]), (0, 4), "DFU_GETSTATUS during the erase: OK, dfuDNBUSY")
        self.assertGreaterEqual(busy_ms, b.flash.erase_ms, "the erase ran after the reply")
        self.assertGreaterEqual(poll_ms, busy_ms, "bwPollTimeout %d ms covers the %.0f ms the board was busy"
                                % (poll_ms, busy_ms))
        self.assertEqual(b.flash.erased, [(0x100, 0)], "sector 0 of the other bank erased once")
        self.assertEqual(bytes(b.uc.mem_read(0x08100000, len(block))), block)
        st = self.control(b, 0xA1, 3, 0, 1, 6)
        self.assertEqual((st[0], st[4], st[1] | st[2] << 8 | st[3] << 16), (0, 5, 0),
                         "DFU_GETSTATUS after bwPollTimeout: OK, dfuDNLOAD-IDLE, no wait")

    def test_interrupt_wiring(self):
        # RM0399 vector table position 77 = OTG_HS; ARMv7-M NVIC: enable bit
        # 77 % 32 of ISER2, priority byte 77 % 4 of IPR19 (upper 4 bits on
        # the M7's 16 levels); the core's global and per-cause masks.
        b = booted()
        entry = struct.unpack("<I", bytes(b.uc.mem_read(0x08000000 + 4 * (16 + 77), 4)))[0]
        self.assertEqual(entry, b.sym("tdc_disco_usb_irq") | 1)
        self.assertTrue(b.scs.nvic_enabled(77))
        self.assertEqual(sum(bin(b.scs.v[0xE100 + 4 * i]).count("1") for i in range(5)), 1, "only OTG_HS enabled")
        prio = b.scs.v[0xE400 + 4 * 19] >> 8 & 0xFF
        self.assertTrue(prio and not prio & 0xF, "a priority in the implemented upper nibble")
        self.assertEqual(b.usb.v[0x8] & 1, 1, "GAHBCFG.GINTMSK")
        self.assertEqual(b.usb.v[0x18], (1 << 4) | (1 << 12) | (1 << 13), "GINTMSK: RXFLVL, USBRST, ENUMDNE")

    def test_no_host_before_core_reset(self):
        # The model refuses a host before the core is set up: what the
        # driver does in tdc_board_init is what makes enumeration possible.
        b = Disco(ELF)
        with self.assertRaisesRegex(EmuError, "ULPI pin|no HS device"):
            b.usb.bus_reset()


class ResetCause(unittest.TestCase):
    # RM0399 RCC_RSR bits; tdc_reset_cause_t values from tdc_board.h.
    POR, BOR, PIN, SFT1, IWDG1, WWDG1 = 1 << 23, 1 << 21, 1 << 22, 1 << 24, 1 << 26, 1 << 28
    CASES = [(POR | BOR | PIN | (1 << 19) | (1 << 20) | (1 << 17), 1),  # power-on
             (BOR | PIN, 5),  # brown-out
             (PIN, 2), (SFT1 | PIN, 3), (IWDG1 | PIN, 4), (WWDG1 | PIN, 4), (0, 0)]

    def test_order(self):
        for rsr, want in self.CASES:
            b = Disco(ELF, rsr=rsr)
            self.assertEqual(b.call("tdc_board_reset_cause"), want, "RCC_RSR 0x%08x" % rsr)
            self.assertEqual(b.rcc.v[0xD0], 0, "flags cleared (RMVF)")


class StageTiming(unittest.TestCase):
    """The frame loop's per-stage timing on the DISCO: tdc_board_cycles()
    is DWT_CYCCNT, counting since tdc_board_init set DEMCR.TRCENA and
    DWT_CTRL.CYCCNTENA (ARMv7-M ARM C1.8); the loop's accounting
    (tdc_fw_time_stage/tdc_fw_time_frame, tdc_fw_log.c) logs one line of
    mean cycles per frame and stage every 64 frames to USART1."""
    STAGE = {"decode": 0, "family": 1, "lcd": 2, "show": 3}

    def test_dwt_cycles_logged_per_stage(self):
        b = Disco(ELF)
        b.run_reset()
        self.assertTrue(b.scs.v[0xEDFC] >> 24 & 1, "DEMCR.TRCENA")
        self.assertTrue(b.scs.v[0x1000] & 1, "DWT_CTRL.CYCCNTENA")
        b.scs.cyc_step = 0
        b.scs.cyc = 0xFFFFF000  # the counter wraps during the run
        self.assertEqual(b.call("tdc_board_cycles"), 0xFFFFF000, "tdc_board_cycles reads DWT_CYCCNT")
        # per frame: decode 2 x 1500 + 700, family 9000 + k, lcd 4000, show 6,666,666 (one 60 Hz frame at 400 MHz)
        spend = {"decode": [1500, 1500, 700], "family": [9000], "lcd": [4000], "show": [6666666]}
        mark = len(b.usart1.tx)
        for k in range(64):
            for stage, chunks in spend.items():
                for c in chunks:
                    t = b.call("tdc_board_cycles")
                    b.scs.cyc += c + (k if stage == "family" else 0)
                    self.assertEqual(b.call("tdc_fw_time_stage", self.STAGE[stage], t), b.scs.cyc & 0xFFFFFFFF)
            if k < 63:
                b.call("tdc_fw_time_frame")
                self.assertEqual(b.usart1.tx[mark:], b"", "no timing line before 64 frames")
        b.call("tdc_fw_time_frame")
        text = b.usart1.tx[mark:].decode()
        want = "cycles/frame: decode 3700 family %d lcd 4000 show 6666666" % (9000 + sum(range(64)) // 64)
        self.assertIn(want + "\r\n", text)
        # the next 64 frames start from zero
        mark = len(b.usart1.tx)
        for _ in range(64):
            b.call("tdc_fw_time_frame")
        self.assertEqual(b.usart1.tx[mark:], b"", "nothing spent: no line")


class LogAndFault(unittest.TestCase):
    def test_uart_log(self):
        b = booted()
        text = b.uart_text()
        self.assertIn("power-on\r\n", text)
        self.assertIn("option bit BCM4 is set", text, "the model's option bytes boot the M4")
        self.assertIn("stm32h747i-disco:", text)
        brr = b.last("USART1", "BRR")
        baud = b.rcc.clocks()["pclk2"] / brr  # USART16SEL = 0: rcc_pclk2; oversampling 16
        self.assertLess(abs(baud - 115200) / 115200, 0.01)
        self.assertEqual((b.gpio[0].mode(9), b.gpio[0].af(9), b.gpio[0].mode(10), b.gpio[0].af(10)), (2, 7, 2, 7))

    def test_fault_vectors_and_report(self):
        b = Disco(ELF)
        b.run_reset()
        vec = struct.unpack("<7I", bytes(b.uc.mem_read(0x08000000, 28)))
        entry = b.sym("tdc_disco_fault_entry") | 1
        self.assertEqual(vec[3:7], (entry,) * 4, "HardFault, MemManage, BusFault, UsageFault")
        frame = 0x24070000
        b.uc.mem_write(frame, struct.pack("<8I", 0, 1, 2, 3, 12, 0x08004321, 0x08001234, 0x01000000))
        b.scs.v[0xED28] = 0x00008200  # CFSR: BFARVALID | PRECISERR
        b.scs.v[0xED38] = 0xC0000004
        b.uart_mark = len(b.usart1.tx)
        b.call("tdc_disco_fault_report", frame, 5)
        self.assertTrue(b.scs.reset_requested)
        text = b.usart1.tx[b.uart_mark:].decode()
        for line in ("fault: exception 0x00000005", "fault: pc 0x08001234", "fault: lr 0x08004321",
                     "fault: cfsr 0x00008200", "fault: bfar 0xc0000004"):
            self.assertIn(line + "\r\n", text)


if __name__ == "__main__":
    ELF = sys.argv.pop(1) if len(sys.argv) > 1 else os.environ.get("DISCO_ELF")
    if not ELF or not os.path.exists(ELF):
        sys.exit("test_disco: run: no firmware ELF given (make BOARD=stm32h747i-disco PANEL=disco-dsi)")
    unittest.main(verbosity=2)
