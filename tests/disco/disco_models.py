"""disco_models.py - register models of the STM32H747 peripherals the DISCO's
board code touches, written from RM0399, the STM32H747xI data sheet
DS12930 and the Cortex-M7 TRM.  Each model knows its register map (an
offset outside it raises), its reset values, the ready/status bits the
firmware polls, and the order rules the reference manual states; a broken
rule raises EmuError naming the rule.
"""


class EmuError(Exception):
    pass


# DS12930 table "General operating conditions": maximum clocks per voltage
# scale (CPU, AXI/AHB, APB) in MHz.  VOS0 exists only on the LDO supply
# (DS12930 note, RM0399 chapter "Power control": overdrive needs the LDO).
VOS_LIMITS_MHZ = {0: (480, 240, 120), 1: (400, 200, 100), 2: (300, 150, 75), 3: (200, 100, 50)}
# RM0399 embedded-flash chapter, table "FLASH recommended number of wait states and
# programming delay": (max AXI MHz, LATENCY, WRHIGHFREQ) per VOS.
FLASH_WS = {
    0: [(70, 0, 0), (140, 1, 1), (185, 2, 1), (210, 2, 2), (225, 3, 2), (240, 4, 2)],
    1: [(70, 0, 0), (140, 1, 1), (185, 2, 1), (210, 2, 2), (225, 3, 2)],
    2: [(55, 0, 0), (110, 1, 1), (165, 2, 1), (225, 3, 2)],
    3: [(45, 0, 0), (90, 1, 1), (135, 2, 1), (180, 3, 2), (225, 4, 2)],
}


def ahb_div(code):
    """HPRE / D1CPRE encoding (RM0399 RCC_D1CFGR): 0xxx = 1, 1000 = 2 ... 1111 = 512."""
    return 1 if code < 8 else [2, 4, 8, 16, 64, 128, 256, 512][code - 8]


def apb_div(code):
    """D1PPRE / D2PPREx / D3PPRE encoding: 0xx = 1, 100 = 2 ... 111 = 16."""
    return 1 if code < 4 else [2, 4, 8, 16][code - 4]


class Model:
    name = "?"
    base = 0
    size = 0x400
    clock = None  # (RCC enable register, bit) that must be set before any access
    regs = {}  # offset -> (name, reset value)

    def __init__(self, emu):
        self.emu = emu
        self.v = {off: reset for off, (_n, reset) in self.regs.items()}

    def reg_name(self, off):
        if off not in self.regs:
            raise EmuError("%s+0x%03x: not a register of %s (RM0399 register map)" % (self.name, off, self.name))
        return self.regs[off][0]

    def byte_ok(self, off, size):
        return False

    def check_clock(self):
        if self.clock and not self.emu.rcc.enabled(*self.clock):
            raise EmuError("%s accessed with its clock off (RCC_%s bit %d clear): reads 0, writes lost"
                           % (self.name, self.clock[0], self.clock[1]))

    def read(self, off):
        return self.v[off]

    def write(self, off, value):
        self.v[off] = value

    def off(self, name):
        for off, (n, _r) in self.regs.items():
            if n == name:
                return off
        raise KeyError(name)

    def get(self, name):
        return self.v[self.off(name)]


# ---------------------------------------------------------------------------
# RCC: RM0399 chapter "Reset and clock control (RCC)"
# ---------------------------------------------------------------------------
class Rcc(Model):
    name, base = "RCC", 0x58024400
    regs = {0x00: ("CR", 0x0000C025), 0x04: ("HSICFGR", 0x40000000), 0x08: ("CRRCR", 0), 0x0C: ("CSICFGR", 0x20000000),
            0x10: ("CFGR", 0), 0x18: ("D1CFGR", 0), 0x1C: ("D2CFGR", 0), 0x20: ("D3CFGR", 0),
            0x28: ("PLLCKSELR", 0x02020200), 0x2C: ("PLLCFGR", 0x01FF0000),
            0x30: ("PLL1DIVR", 0x01010280), 0x34: ("PLL1FRACR", 0), 0x38: ("PLL2DIVR", 0x01010280),
            0x3C: ("PLL2FRACR", 0), 0x40: ("PLL3DIVR", 0x01010280), 0x44: ("PLL3FRACR", 0),
            0x4C: ("D1CCIPR", 0), 0x50: ("D2CCIP1R", 0), 0x54: ("D2CCIP2R", 0), 0x58: ("D3CCIPR", 0),
            0x60: ("CIER", 0), 0x64: ("CIFR", 0), 0x68: ("CICR", 0), 0x70: ("BDCR", 0), 0x74: ("CSR", 0),
            0x7C: ("AHB3RSTR", 0), 0x80: ("AHB1RSTR", 0), 0x84: ("AHB2RSTR", 0), 0x88: ("AHB4RSTR", 0),
            0x8C: ("APB3RSTR", 0), 0x90: ("APB1LRSTR", 0), 0x94: ("APB1HRSTR", 0), 0x98: ("APB2RSTR", 0),
            0x9C: ("APB4RSTR", 0), 0xA0: ("GCR", 0), 0xD0: ("RSR", 0),
            0xD4: ("AHB3ENR", 0), 0xD8: ("AHB1ENR", 0), 0xDC: ("AHB2ENR", 0), 0xE0: ("AHB4ENR", 0),
            0xE4: ("APB3ENR", 0), 0xE8: ("APB1LENR", 0), 0xEC: ("APB1HENR", 0), 0xF0: ("APB2ENR", 0),
            0xF4: ("APB4ENR", 0)}
    # RCC_RSR after a power-on reset: POR, BOR, pin, D1, D2 and CPU flags all
    # set (RM0399 RCC chapter, "reset source identification").
    RSR_POWER_ON = (1 << 23) | (1 << 21) | (1 << 22) | (1 << 19) | (1 << 20) | (1 << 17)
    PLL_FIELDS = {1: (0x30, 0, 4), 2: (0x38, 4, 12), 3: (0x40, 8, 20)}  # DIVR reg, PLLCFGR shift, DIVM shift

    def __init__(self, emu, hse_hz, rsr):
        super().__init__(emu)
        self.hse_hz = hse_hz
        self.v[0xD0] = self.RSR_POWER_ON if rsr is None else rsr
        self.switches = []  # (sysclk Hz, VOS) at each SW change

    def enabled(self, reg, bit):
        return bool(self.v[self.off(reg)] >> bit & 1)

    def pll_on(self, n):
        return bool(self.v[0] >> (22 + 2 * n) & 1)

    def pll(self, n):
        """(ref, vco, p, q, r) in Hz of PLLn from the current register values (RM0399 RCC 'PLL' formulas)."""
        divr, cfg_sh, m_sh = self.PLL_FIELDS[n]
        src = self.v[0x28] & 3
        fin = {0: 64000000, 1: 4000000, 2: self.hse_hz}.get(src, 0)
        divm = self.v[0x28] >> m_sh & 0x3F
        d = self.v[divr]
        divn = (d & 0x1FF) + 1
        ref = fin // divm if divm else 0
        vco = ref * divn
        return ref, vco, vco // ((d >> 9 & 0x7F) + 1), vco // ((d >> 16 & 0x7F) + 1), vco // ((d >> 24 & 0x7F) + 1)

    def check_pll(self, n):
        divr, cfg_sh, m_sh = self.PLL_FIELDS[n]
        cfg = self.v[0x2C] >> cfg_sh & 0xF
        divm = self.v[0x28] >> m_sh & 0x3F
        if divm == 0:
            raise EmuError("PLL%d enabled with DIVM%d = 0 (prescaler disabled)" % (n, n))
        if (self.v[0x28] & 3) == 2 and not (self.v[0] >> 17 & 1):
            raise EmuError("PLL%d enabled on HSE before HSERDY" % n)
        ref, vco, p, q, r = self.pll(n)
        rge, vcosel = cfg >> 2 & 3, cfg >> 1 & 1
        lo, hi = [(1e6, 2e6), (2e6, 4e6), (4e6, 8e6), (8e6, 16e6)][rge]
        if not lo <= ref <= hi:
            raise EmuError("PLL%d input %d Hz outside PLL%dRGE range %d-%d Hz" % (n, ref, n, lo, hi))
        vlo, vhi = (150e6, 420e6) if vcosel else (192e6, 960e6)
        if not vlo <= vco <= vhi:
            raise EmuError("PLL%d VCO %d Hz outside the %s VCO range" % (n, vco, "medium" if vcosel else "wide"))
        divn = (self.v[divr] & 0x1FF) + 1
        if not 4 <= divn <= 512:
            raise EmuError("PLL%d DIVN %d out of 4..512" % (n, divn))
        if n == 1 and (self.v[divr] >> 9 & 0x7F) % 2 == 0:
            raise EmuError("PLL1 DIVP1 field %d: only even division factors are allowed" % (self.v[divr] >> 9 & 0x7F))

    def sysclk(self):
        sws = self.v[0x10] >> 3 & 7
        return {0: 64000000, 1: 4000000, 2: self.hse_hz, 3: self.pll(1)[2]}[sws]

    def clocks(self, sysclk=None, d1=None):
        """cpu, hclk (AXI/AHB), pclk1..4 in Hz."""
        s = self.sysclk() if sysclk is None else sysclk
        d1 = self.v[0x18] if d1 is None else d1
        cpu = s // ahb_div(d1 >> 8 & 0xF)
        hclk = cpu // ahb_div(d1 & 0xF)
        d2, d3 = self.v[0x1C], self.v[0x20]
        return {"cpu": cpu, "hclk": hclk, "pclk3": hclk // apb_div(d1 >> 4 & 7), "pclk1": hclk // apb_div(d2 >> 4 & 7),
                "pclk2": hclk // apb_div(d2 >> 8 & 7), "pclk4": hclk // apb_div(d3 >> 4 & 7)}

    def check_limits(self, clk):
        pwr, flash = self.emu.pwr, self.emu.flash
        vos = pwr.vos()
        if not pwr.vos_ready_seen:
            raise EmuError("clock raised before VOSRDY was read back after the last VOS change (RM0399 PWR "
                           "'Voltage scaling': wait VOSRDY)")
        cpu_max, bus_max, apb_max = (x * 1000000 for x in VOS_LIMITS_MHZ[vos])
        if clk["cpu"] > cpu_max or clk["hclk"] > bus_max or max(clk[k] for k in ("pclk1", "pclk2", "pclk3", "pclk4")) > apb_max:
            raise EmuError("clocks %s exceed VOS%d limits %s MHz (DS12930)" % (
                {k: v // 1000000 for k, v in clk.items()}, vos, VOS_LIMITS_MHZ[vos]))
        need = None
        for fmax, lat, wrh in FLASH_WS[vos]:
            if clk["hclk"] <= fmax * 1000000:
                need = (lat, wrh)
                break
        if need is None or flash.latency_seen < need[0]:
            raise EmuError("AXI clock %d Hz at VOS%d needs %s flash wait states; FLASH_ACR read back %d (RM0399 "
                           "FLASH wait-state table)" % (clk["hclk"], vos, need and need[0], flash.latency_seen))

    def write(self, off, value):
        old = self.v[off]
        if off == 0x00:  # CR
            for n in (1, 2, 3):
                on = value >> (22 + 2 * n) & 1
                if on and not (old >> (22 + 2 * n) & 1):
                    self.check_pll(n)
            if (old >> 16 & 1) and not (value >> 16 & 1) and ((self.v[0x10] >> 3 & 7) == 2 or self.pll_on(1)):
                raise EmuError("HSE switched off while in use")
            ro = (1 << 2) | (1 << 17) | (1 << 25) | (1 << 27) | (1 << 29) | (1 << 14) | (1 << 15)
            value = (value & ~ro) | (old & ro)
            value = (value & ~(1 << 17)) | ((value >> 16 & 1) << 17)  # HSERDY follows HSEON
            for n in (1, 2, 3):
                on = value >> (22 + 2 * n) & 1
                value = (value & ~(1 << (23 + 2 * n))) | (on << (23 + 2 * n))
        elif off == 0x28:  # PLLCKSELR
            for n, (_d, _c, m_sh) in self.PLL_FIELDS.items():
                if self.pll_on(n) and ((old ^ value) & ((0x3F << m_sh) | 3)):
                    raise EmuError("RCC_PLLCKSELR DIVM%d/PLLSRC changed while PLL%d is on (RM0399: written only "
                                   "when the PLL is disabled)" % (n, n))
        elif off == 0x2C:  # PLLCFGR
            for n, (_d, cfg_sh, _m) in self.PLL_FIELDS.items():
                mask = (0xF << cfg_sh) | (7 << (16 + 3 * (n - 1)))
                if self.pll_on(n) and ((old ^ value) & mask):
                    raise EmuError("RCC_PLLCFGR PLL%d fields changed while PLL%d is on (RM0399)" % (n, n))
        elif off in (0x30, 0x34, 0x38, 0x3C, 0x40, 0x44):
            n = {0x30: 1, 0x34: 1, 0x38: 2, 0x3C: 2, 0x40: 3, 0x44: 3}[off]
            if self.pll_on(n) and old != value and off in (0x30, 0x38, 0x40):
                raise EmuError("RCC_PLL%dDIVR written while PLL%d is on (RM0399: written only when disabled)" % (n, n))
        elif off == 0x10:  # CFGR
            sw = value & 7
            if sw == 3 and not (self.v[0] >> 25 & 1):
                raise EmuError("SYSCLK switched to PLL1 before PLL1RDY")
            if sw == 2 and not (self.v[0] >> 17 & 1):
                raise EmuError("SYSCLK switched to HSE before HSERDY")
            new_sys = {0: 64000000, 1: 4000000, 2: self.hse_hz, 3: self.pll(1)[2]}[sw]
            self.check_limits(self.clocks(new_sys))
            value = (value & ~(7 << 3)) | (sw << 3)
            self.switches.append((new_sys, self.emu.pwr.vos()))
        elif off == 0x18:  # D1CFGR
            self.check_limits(self.clocks(None, value))
        elif off == 0xD0:  # RSR: RMVF clears every flag
            value = 0 if value >> 16 & 1 else old
        self.v[off] = value


# ---------------------------------------------------------------------------
# PWR: RM0399 chapter "Power control (PWR)"
# ---------------------------------------------------------------------------
class Pwr(Model):
    name, base = "PWR", 0x58024800
    regs = {0x00: ("CR1", 0xF000C000), 0x04: ("CSR1", 0x00004000), 0x08: ("CR2", 0), 0x0C: ("CR3", 0x00000006),
            0x10: ("CPU1CR", 0), 0x14: ("CPU2CR", 0), 0x18: ("D3CR", 0x00004000), 0x20: ("WKUPCR", 0),
            0x24: ("WKUPFR", 0), 0x28: ("WKUPEPR", 0)}
    SUPPLY_BITS = 0x3F  # BYPASS, LDOEN, SDEN, SDEXTHP, SDLEVEL: written once after power-on
    # The DISCO (UM2411, MB1248 power section) feeds VCORE from the internal
    # SMPS directly: SDEN = 1, LDOEN = 0, BYPASS = 0.
    WIRING = {"smps": 0x4, "ldo": 0x2}

    def __init__(self, emu, supply):
        super().__init__(emu)
        self.supply = supply
        self.cr3_written = False
        self.actvosrdy_seen = False
        self.vos_ready_seen = True  # reset state: VOS3, ready
        self.reads_until_ready = 0
        self.overdrive = False

    def vos(self):
        """0..3 as in the data sheet (VOS0 = VOS1 field + SYSCFG ODEN)."""
        field = self.v[0x18] >> 14 & 3
        if field == 3 and self.overdrive:
            return 0
        return {1: 3, 2: 2, 3: 1, 0: 3}[field]

    def read(self, off):
        if off == 0x04:  # CSR1: ACTVOSRDY a few reads after the supply write
            if self.cr3_written and self.reads_until_ready == 0:
                self.v[4] |= 1 << 13
            else:
                self.v[4] &= ~(1 << 13)
                self.reads_until_ready = max(0, self.reads_until_ready - 1)
            if self.v[4] >> 13 & 1:
                self.actvosrdy_seen = True
        if off == 0x18:
            if self.reads_until_ready:
                self.reads_until_ready -= 1
                self.v[0x18] &= ~(1 << 13)
            else:
                self.v[0x18] |= 1 << 13
                self.vos_ready_seen = True
        return self.v[off]

    def write(self, off, value):
        if off == 0x0C:
            if (value ^ self.v[0x0C]) & self.SUPPLY_BITS and self.cr3_written:
                raise EmuError("PWR_CR3 supply configuration written twice: it is write-once after power-on "
                               "(RM0399 PWR 'Power supply configuration')")
            if (value & 7) != self.WIRING[self.supply]:
                raise EmuError("PWR_CR3 supply 0x%x does not match the DISCO's %s wiring (0x%x): ACTVOSRDY would "
                               "never set" % (value & 7, self.supply, self.WIRING[self.supply]))
            self.cr3_written = True
            self.reads_until_ready = 2
        elif off == 0x18:
            if not self.cr3_written or not self.actvosrdy_seen:
                raise EmuError("PWR_D3CR VOS written before the supply configuration and ACTVOSRDY (RM0399 PWR)")
            if (value ^ self.v[0x18]) & (3 << 14):
                self.vos_ready_seen = False
                self.reads_until_ready = 2
            value = (value & ~(1 << 13)) | (self.v[0x18] & (1 << 13))
        self.v[off] = value


class Syscfg(Model):
    name, base = "SYSCFG", 0x58000400
    clock = ("APB4ENR", 1)
    regs = {0x04: ("PMCR", 0), 0x08: ("EXTICR1", 0), 0x20: ("CFGR", 0), 0x2C: ("PWRCR", 0), 0x70: ("UR0", 0)}

    def write(self, off, value):
        if off == 0x2C and value & 1:
            if self.emu.pwr.supply != "ldo":
                raise EmuError("SYSCFG_PWRCR.ODEN (VOS0 overdrive) on the SMPS supply: VOS0 needs the LDO (RM0399 "
                               "PWR 'Voltage scaling', DS12930)")
            self.emu.pwr.overdrive = True
            self.emu.pwr.vos_ready_seen = False
            self.emu.pwr.reads_until_ready = 2
        self.v[off] = value


# ---------------------------------------------------------------------------
# FLASH: RM0399 chapter "Embedded flash memory (FLASH)".  Two banks of
# 8 x 128 KiB sectors; register set 1 serves the bank at 0x08000000, set 2
# (+0x100) the bank at 0x08100000 (SWAP_BANK = 0).  Rules: CRx writable
# only after the KEYRx sequence; programming only with PG set, in whole
# 256-bit words (8 sequential word writes), only into erased words;
# sector erase only while idle; nothing written to the bank the core runs
# from; option bytes only after the OPTKEYR sequence.  Power can be cut
# after a given number of erase/program operations (PowerLoss).
# ---------------------------------------------------------------------------
class PowerLoss(Exception):
    pass


class Flash(Model):
    name, base = "FLASH", 0x52002000
    regs = {0x00: ("ACR", 0x37), 0x04: ("KEYR1", 0), 0x08: ("OPTKEYR", 0), 0x0C: ("CR1", 0x31), 0x10: ("SR1", 0),
            0x14: ("CCR1", 0), 0x18: ("OPTCR", 1), 0x1C: ("OPTSR_CUR", 0x1C6AAF0 | (1 << 23)), 0x20: ("OPTSR_PRG", 0),
            0x104: ("KEYR2", 0), 0x10C: ("CR2", 0x31), 0x110: ("SR2", 0), 0x114: ("CCR2", 0)}
    BANK = 1 << 20
    SECTOR = 128 << 10
    KEYS, OPTKEYS = (0x45670123, 0xCDEF89AB), (0x08192A3B, 0x4C5D6E7F)

    def __init__(self, emu):
        super().__init__(emu)
        self.latency_seen = 7  # reset value, read back by definition
        self.key_state = {0: 0, 0x100: 0}
        self.optkey_state = 0
        self.busy_reads = {0: 0, 0x100: 0}
        self.erased = []  # (bank offset, sector)
        self.programmed = set()  # flash word addresses
        self.pending = []  # word writes of the flash word being filled
        self.ops = 0
        self.power_cut_at = None  # ops count at which power fails
        self.stuck_busy = False
        self.running_bank_writes = 0
        # A sector erase lasts ERASE_MS of model time: when the bank stops
        # reading busy the model clock (DWT) jumps to the erase's end, as if
        # the core had polled all along.  2 s, inside the "up to seconds" of
        # DS12930 and below the driver's 4 s bound (TDC_DISCO_FLASH_ERASE_MS).
        self.erase_ms = 2000
        self.erase_end = {0: 0, 0x100: 0}  # model cycle at which each bank's erase ends

    def other_set(self):
        """Register-set offset of the physical bank mapped at 0x08100000:
        registers follow the physical bank, SWAP_BANK moves the addresses."""
        return 0 if self.v[0x1C] >> 31 else 0x100

    def read(self, off):
        if off == 0:
            self.latency_seen = self.v[0] & 0xF
        if off in (0x10, 0x110):
            b = off - 0x10
            if self.stuck_busy or self.busy_reads[b]:
                self.busy_reads[b] = max(0, self.busy_reads[b] - 1)
                return self.v[off] | 0x5  # BSY, QW
            self.emu.scs.cyc = max(self.emu.scs.cyc, self.erase_end[b])
            return self.v[off] & ~0x5
        if off == 0x1C and self.busy_reads.get("opt"):
            self.busy_reads["opt"] -= 1
            return self.v[off] | 1
        return self.v[off]

    def tick(self):
        self.ops += 1
        if self.power_cut_at is not None and self.ops >= self.power_cut_at:
            self.emu.power_lost = True
            self.emu.uc.emu_stop()
            raise PowerLoss()

    def write(self, off, value):
        if off == 0 and (value & 0xF) != (self.v[0] & 0xF):
            # Until the new LATENCY is read back, assume the worst (RM0399:
            # check it is taken into account by reading FLASH_ACR).
            self.latency_seen = min(self.latency_seen, value & 0xF)
        if off in (0x04, 0x104):
            b = off - 0x04
            if self.key_state[b] == 0 and value == self.KEYS[0]:
                self.key_state[b] = 1
            elif self.key_state[b] == 1 and value == self.KEYS[1]:
                self.key_state[b] = 2
                self.v[b + 0x0C] &= ~1
            else:
                raise EmuError("FLASH_KEYR%d: wrong unlock sequence (CR stays locked until reset)" % (1 + b // 0x100))
            return
        if off in (0x0C, 0x10C):
            b = off - 0x0C
            if self.v[off] & 1:
                raise EmuError("FLASH_CR%d written while locked" % (1 + b // 0x100))
            if value & (1 << 7) and value & (1 << 2):  # SER + START
                if self.busy_reads[b] or self.stuck_busy:
                    raise EmuError("sector erase started while the bank is busy")
                if b != self.other_set():
                    raise EmuError("sector erase in the bank the core runs from (register set %d)" % (1 + b // 0x100))
                sector = value >> 8 & 7
                base = 0x08000000 + self.BANK + sector * self.SECTOR
                try:
                    self.tick()
                except PowerLoss:
                    self.emu.uc.mem_write(base, b"\xff" * (self.SECTOR // 2))  # half erased
                    raise
                self.emu.uc.mem_write(base, b"\xff" * self.SECTOR)
                self.programmed = {a for a in self.programmed if not base <= a < base + self.SECTOR}
                self.erased.append((b, sector))
                self.busy_reads[b] = 3
                self.erase_end[b] = self.emu.scs.cyc + self.erase_ms * self.emu.rcc.clocks()["cpu"] // 1000
                value &= ~(1 << 7)
            if value & 2 and (value >> 4 & 3) != 3:
                raise EmuError("programming with PSIZE %d: the DISCO's 3.3 V supply takes x64 (PSIZE 3)"
                               % (value >> 4 & 3))
            if not value & 2 and self.pending:
                raise EmuError("PG cleared with a partial flash word in the write buffer (%d of 8 words)"
                               % len(self.pending))
            if value & 1:
                self.key_state[b] = 0
        if off == 0x20 and self.v[0x18] & 1:
            raise EmuError("FLASH_OPTSR_PRG written with the option bytes locked")
        if off == 0x08:
            if self.optkey_state == 0 and value == self.OPTKEYS[0]:
                self.optkey_state = 1
            elif self.optkey_state == 1 and value == self.OPTKEYS[1]:
                self.optkey_state = 2
                self.v[0x18] &= ~1
            else:
                raise EmuError("FLASH_OPTKEYR: wrong unlock sequence")
            return
        if off == 0x18:
            if self.v[0x18] & 1 and not value & 1:
                raise EmuError("FLASH_OPTCR unlocked by a write instead of the OPTKEYR sequence")
            if value & 2:
                if self.v[0x18] & 1:
                    raise EmuError("OPTSTART with the option bytes locked")
                self.tick()
                self.v[0x1C] = (self.v[0x1C] & 0x7FFFFFFF) | (self.v[0x20] & 0x80000000)
                self.busy_reads["opt"] = 2
                value &= ~2
            if value & 1:
                self.optkey_state = 0
        self.v[off] = value

    def mem_write(self, uc, access, addr, size, value, data):
        """Hook on stores to the flash address range."""
        try:
            if addr < 0x08000000 + self.BANK:
                self.running_bank_writes += 1
                raise EmuError("store to 0x%08x: the bank the core runs from" % addr)
            cr = 0x0C + self.other_set()
            if not self.v[cr] & 2:
                raise EmuError("store to flash 0x%08x without PG in FLASH_CR%d" % (addr, 1 + cr // 0x100))
            if size != 4 or addr & 3:
                raise EmuError("%d-byte store to flash 0x%08x: program 32-bit words" % (size, addr))
            word = addr & ~31
            if self.pending and (word != self.pending[0] & ~31 or addr != self.pending[-1] + 4):
                raise EmuError("flash word writes not sequential within one 256-bit word (0x%08x)" % addr)
            if not self.pending and addr & 31:
                raise EmuError("flash word programming must start at its first 32-bit word (0x%08x)" % addr)
            if word in self.programmed:
                raise EmuError("flash word 0x%08x programmed twice without an erase (ECC)" % word)
            if not self.pending and bytes(uc.mem_read(word, 32)) != b"\xff" * 32:
                raise EmuError("flash word 0x%08x not erased" % word)
            self.pending.append(addr)
            if len(self.pending) == 8:
                self.tick()
                self.programmed.add(word)
                self.pending = []
                self.busy_reads[self.other_set()] = 2
        except PowerLoss:
            pass
        except EmuError as e:
            self.emu.fail(str(e))
        return True


# ---------------------------------------------------------------------------
# FMC SDRAM controller: RM0399 chapter "Flexible memory controller (FMC)"
# ---------------------------------------------------------------------------
class Fmc(Model):
    name, base, size = "FMC", 0x52004000, 0x1000
    clock = ("AHB3ENR", 12)
    regs = {0x00: ("BCR1", 0x000030DB), 0x04: ("BTR1", 0x0FFFFFFF), 0x08: ("BCR2", 0x000030D2), 0x0C: ("BTR2", 0x0FFFFFFF),
            0x80: ("PCR", 0x18), 0x84: ("SR", 0x40), 0x140: ("SDCR1", 0x2D0), 0x144: ("SDCR2", 0x2D0),
            0x148: ("SDTR1", 0x0FFFFFFF), 0x14C: ("SDTR2", 0x0FFFFFFF), 0x150: ("SDCMR", 0), 0x154: ("SDRTR", 0),
            0x158: ("SDSR", 0)}

    def __init__(self, emu):
        super().__init__(emu)
        self.commands = []  # (mode, nrfs, mrd, instructions since the previous command)
        self.insns = 0
        self.counting = None

    def sdram_ready(self):
        modes = [c[0] for c in self.commands]
        return modes[:4] == [1, 2, 3, 4] and (self.v[0x154] >> 1 & 0x1FFF) != 0

    def _count(self, uc, addr, size, data):
        self.insns += 1

    def write(self, off, value):
        if off == 0x150:
            if not (self.v[0] >> 31 & 1):
                raise EmuError("FMC_SDCMR command with FMC_BCR1.FMCEN clear (RM0399 FMC: the controller is off)")
            if self.v[0x144] == 0x2D0 or self.v[0x14C] == 0x0FFFFFFF:
                raise EmuError("SDRAM command before FMC_SDCR2/SDTR2 were programmed (RM0399 FMC 'SDRAM "
                               "initialization' steps 1-2)")
            if not (value >> 3 & 1) or value >> 4 & 1:
                raise EmuError("SDRAM command not targeted at bank 2 only (the DISCO's SDRAM is on SDNE1/SDCKE1)")
            mode = value & 7
            if self.counting is not None:
                self.emu.uc.hook_del(self.counting)
                self.counting = None
            self.commands.append((mode, (value >> 5 & 0xF) + 1, value >> 9 & 0x3FFF, self.insns))
            if mode == 1:
                from unicorn import UC_HOOK_CODE
                self.insns = 0
                self.counting = self.emu.uc.hook_add(UC_HOOK_CODE, self._count)
        elif off == 0x154 and not [c for c in self.commands if c[0] == 4]:
            raise EmuError("FMC_SDRTR programmed before the load-mode-register command (RM0399 FMC step 8)")
        self.v[off] = value


# ---------------------------------------------------------------------------
# GPIO: RM0399 chapter "General-purpose I/Os (GPIO)"
# ---------------------------------------------------------------------------
class Gpio(Model):
    size = 0x400
    regs = {0x00: ("MODER", 0xFFFFFFFF), 0x04: ("OTYPER", 0), 0x08: ("OSPEEDR", 0), 0x0C: ("PUPDR", 0), 0x10: ("IDR", 0),
            0x14: ("ODR", 0), 0x18: ("BSRR", 0), 0x1C: ("LCKR", 0), 0x20: ("AFRL", 0), 0x24: ("AFRH", 0)}

    def __init__(self, emu, port):
        self.port = port
        self.name = "GPIO" + "ABCDEFGHIJK"[port]
        self.base = 0x58020000 + 0x400 * port
        self.clock = ("AHB4ENR", port)
        super().__init__(emu)
        if port == 0:
            self.v.update({0x00: 0xABFFFFFF, 0x08: 0x0C000000, 0x0C: 0x64000000})
        if port == 1:
            self.v.update({0x00: 0xFFFFFEBF, 0x08: 0xC0, 0x0C: 0x100})

    def write(self, off, value):
        old = self.v[0x14]
        if off == 0x18:
            self.v[0x14] = (self.v[0x14] | (value & 0xFFFF)) & ~(value >> 16)
        else:
            self.v[off] = value
        if self.v[0x14] != old or off == 0x18:
            self.emu.dsi.gpio_changed(self.port, old, self.v[0x14])

    def mode(self, pin):
        return self.v[0] >> (2 * pin) & 3

    def af(self, pin):
        return self.v[0x20 if pin < 8 else 0x24] >> (4 * (pin & 7)) & 0xF

    def out(self, pin):
        return self.v[0x14] >> pin & 1


# ---------------------------------------------------------------------------
# USART: RM0399 chapter "USART/UART"
# ---------------------------------------------------------------------------
class Usart(Model):
    regs = {0x00: ("CR1", 0), 0x04: ("CR2", 0), 0x08: ("CR3", 0), 0x0C: ("BRR", 0), 0x10: ("GTPR", 0), 0x14: ("RTOR", 0),
            0x18: ("RQR", 0), 0x1C: ("ISR", 0x006000C0), 0x20: ("ICR", 0), 0x24: ("RDR", 0), 0x28: ("TDR", 0),
            0x2C: ("PRESC", 0)}
    TX_PIN = (0, 9, 7)  # PA9 AF7 (UM2411: USART1_TX to the ST-LINK VCP)

    def __init__(self, emu, name, base, clock):
        self.name, self.base, self.clock = name, base, clock
        super().__init__(emu)
        self.tx = bytearray()

    def byte_ok(self, off, size):
        return off == 0x28

    def write(self, off, value):
        ue = self.v[0] & 1
        if off in (0x04, 0x08, 0x0C, 0x2C) and ue:
            raise EmuError("%s %s written while UE = 1 (RM0399 USART: configure with UE = 0)" % (self.name, self.regs[off][0]))
        if off == 0x28:
            if not (ue and self.v[0] >> 3 & 1):
                raise EmuError("%s TDR written with UE or TE clear: the byte is lost" % self.name)
            port, pin, af = self.TX_PIN
            g = self.emu.gpio[port]
            if g.mode(pin) != 2 or g.af(pin) != af:
                raise EmuError("%s transmits but P%s%d is not in AF%d" % (self.name, "ABCDEFGHIJK"[port], pin, af))
            self.tx.append(value & 0xFF)
        if off == 0 and value & 1:
            self.v[0x1C] |= (1 << 21) | ((value >> 2 & 1) << 22)  # TEACK, REACK
        self.v[off] = value

    def text(self):
        return self.tx.decode("latin-1")


# ---------------------------------------------------------------------------
# LTDC: RM0399 chapter "LCD-TFT display controller (LTDC)"
# ---------------------------------------------------------------------------
class Ltdc(Model):
    name, base = "LTDC", 0x50001000
    clock = ("APB3ENR", 3)
    regs = {0x08: ("SSCR", 0), 0x0C: ("BPCR", 0), 0x10: ("AWCR", 0), 0x14: ("TWCR", 0), 0x18: ("GCR", 0x2220),
            0x24: ("SRCR", 0), 0x2C: ("BCCR", 0), 0x34: ("IER", 0), 0x38: ("ISR", 0), 0x3C: ("ICR", 0),
            0x40: ("LIPCR", 0), 0x44: ("CPSR", 0), 0x48: ("CDSR", 0xF)}
    for _l, _b in ((1, 0x84), (2, 0x104)):
        for _o, _n in ((0, "CR"), (4, "WHPCR"), (8, "WVPCR"), (0xC, "CKCR"), (0x10, "PFCR"), (0x14, "CACR"),
                       (0x18, "DCCR"), (0x1C, "BFCR"), (0x28, "CFBAR"), (0x2C, "CFBLR"), (0x30, "CFBLNR"),
                       (0x40, "CLUTWR")):
            regs[_b + _o] = ("L%d%s" % (_l, _n), 0x0607 if _n == "BFCR" else 0)

    def __init__(self, emu):
        super().__init__(emu)
        self.flips = []
        self.cdsr_reads = 0

    def read(self, off):
        if off == 0x48:  # CDSR: VSYNCS for 4 of every 64 reads: a frame, mostly active
            self.cdsr_reads += 1
            return 0xB | (int(self.cdsr_reads % 64 < 4) << 2)
        return self.v[off]

    def write(self, off, value):
        rcc = self.emu.rcc
        if off == 0x18 and value & 1 and not self.v[0x18] & 1:
            # The kernel clock is PLL3R (RM0399 RCC 'ltdc_ker_ck'): it must run.
            if not (rcc.v[0] >> 29 & 1 and rcc.v[0x2C] >> 24 & 1):
                raise EmuError("LTDC enabled without PLL3 locked and DIVR3EN: no pixel clock")
            hs, vs = [self.v[o] >> 16 & 0xFFF for o in (8, 0xC, 0x10, 0x14)], [self.v[o] & 0x7FF for o in (8, 0xC, 0x10, 0x14)]
            if not (hs == sorted(hs) and vs == sorted(vs) and len(set(hs)) == 4 and len(set(vs)) == 4):
                raise EmuError("LTDC timing registers not increasing (SSCR < BPCR < AWCR < TWCR, RM0399 LTDC)")
        if off == 0x84 and value & 1:
            fb = self.v[0xAC]
            ram = (0x24000000 <= fb < 0x24080000) or (0xD0000000 <= fb < 0xD2000000 and self.emu.fmc.sdram_ready())
            if not ram:
                raise EmuError("LTDC layer 1 enabled on frame buffer 0x%08x: not memory the LTDC can read" % fb)
            if self.v[0x94] > 7:
                raise EmuError("L1PFCR: no such pixel format")
            bpp = [4, 3, 2, 2, 2, 1, 1, 2][self.v[0x94]]
            width = (self.v[0x88] >> 16 & 0xFFF) - (self.v[0x88] & 0xFFF) + 1
            if (self.v[0xB0] & 0x1FFF) > width * bpp + 7:
                raise EmuError("L1CFBLR line length larger than the window (+7, RM0399 LTDC_LxCFBLR)")
        if off == 0x24 and value & 2 and self.v[0x84] & 1:
            self.emu.scs.check_flip(self.v[0xAC], self.v[0xB0] >> 16, self.v[0xB4] & 0x7FF)
            self.flips.append((self.v[0xAC], self.v[0xB0], self.v[0xB4]))
        if off == 0x24:
            value = 0
        self.v[off] = value


# ---------------------------------------------------------------------------
# DSI host + wrapper: RM0399 chapter "DSI Host (DSI)" (Synopsys DesignWare
# host; wrapper PLL formula and ranges as RM0399 states them:
# lane rate = HSE x NDIV / (IDF x ODF), VCO = 2 x lane rate x ODF in
# 500-1000 MHz, lane rate 31.25-500 Mbit/s, NDIV 10-125, IDF 1-7).
# Behind it, a model of the panel's controller: reset line, ID registers,
# the DCS packets it receives and when.
# ---------------------------------------------------------------------------
class Dsi(Model):
    name, base, size = "DSI", 0x50000000, 0x1000
    clock = ("APB3ENR", 4)
    regs = {}
    for _o, _n in ((0x00, "VR"), (0x04, "CR"), (0x08, "CCR"), (0x0C, "LVCIDR"), (0x10, "LCOLCR"), (0x14, "LPCR"),
                   (0x18, "LPMCR"), (0x2C, "PCR"), (0x30, "GVCIDR"), (0x34, "MCR"), (0x38, "VMCR"), (0x3C, "VPCR"),
                   (0x40, "VCCR"), (0x44, "VNPCR"), (0x48, "VHSACR"), (0x4C, "VHBPCR"), (0x50, "VLCR"),
                   (0x54, "VVSACR"), (0x58, "VVBPCR"), (0x5C, "VVFPCR"), (0x60, "VVACR"), (0x64, "LCCR"),
                   (0x68, "CMCR"), (0x6C, "GHCR"), (0x70, "GPDR"), (0x74, "GPSR"), (0x78, "TCCR0"), (0x7C, "TCCR1"),
                   (0x80, "TCCR2"), (0x84, "TCCR3"), (0x88, "TCCR4"), (0x8C, "TCCR5"), (0x94, "CLCR"),
                   (0x98, "CLTCR"), (0x9C, "DLTCR"), (0xA0, "PCTLR"), (0xA4, "PCONFR"), (0xA8, "PUCR"),
                   (0xAC, "PTTCR"), (0xB0, "PSR"), (0xBC, "ISR0"), (0xC0, "ISR1"), (0xC4, "IER0"), (0xC8, "IER1"),
                   (0xD8, "FIR0"), (0xDC, "FIR1"), (0x100, "VSCR"), (0x400, "WCFGR"), (0x404, "WCR"),
                   (0x408, "WIER"), (0x40C, "WISR"), (0x410, "WIFCR"), (0x418, "WPCR0"), (0x41C, "WPCR1"),
                   (0x420, "WPCR2"), (0x424, "WPCR3"), (0x428, "WPCR4"), (0x430, "WRPCR")):
        regs[_o] = (_n, 0x3133302A if _n == "VR" else 0)
    PANEL_IDS = {"otm8009a": {0xDA: 0x40, 0xDB: 0x00}, "nt35510": {0xDA: 0x00, 0xDB: 0x80},
                 "unknown": {0xDA: 0x00, 0xDB: 0x00}}

    def __init__(self, emu, panel):
        super().__init__(emu)
        self.panel = panel
        self.ids = self.PANEL_IDS[panel]
        self.wfifo = []
        self.rfifo = []
        self.max_return = 0
        self.packets = []  # (data type, bytes, DWT cycle)
        self.reset_release = None
        self.low_since = None

    def lane_rate(self):
        w = self.v[0x430]
        ndiv, idf, odf = w >> 2 & 0x7F, w >> 11 & 0xF, 1 << (w >> 16 & 3)
        return self.emu.rcc.hse_hz * ndiv / (idf * odf) if idf else 0, ndiv, idf, odf

    def ms_since(self, cyc):
        return (self.emu.scs.cyc - cyc) / (self.emu.rcc.clocks()["cpu"] / 1000.0)

    def read(self, off):
        if off == 0x40C:  # WISR: RRS follows REGEN, PLLLS follows an accepted PLLEN
            w = self.v[0x430]
            return ((w >> 24 & 1) << 12) | ((w & 1) << 8)
        if off == 0x74:
            return 0x5 | (0 if self.rfifo else 0x10)
        if off == 0x70:
            if not self.rfifo:
                raise EmuError("DSI_GPDR read with the read FIFO empty (GPSR.PRDFE set)")
            return self.rfifo.pop(0)
        return self.v[off]

    def write(self, off, value):
        if off == 0x430:
            old = self.v[0x430]
            if old & 1 and (old ^ value) & 0x3FFFE:
                raise EmuError("DSI_WRPCR dividers changed while the DSI PLL runs")
            if value & 1 and not old & 1:
                if not value >> 24 & 1:
                    raise EmuError("DSI PLL enabled before the DSI regulator (WRPCR.REGEN, WISR.RRS)")
                self.v[0x430] = value
                lane, ndiv, idf, odf = self.lane_rate()
                vco = lane * 2 * odf
                if not (10 <= ndiv <= 125 and 1 <= idf <= 7 and 500e6 <= vco <= 1000e6 and 31.25e6 <= lane <= 500e6):
                    raise EmuError("DSI PLL NDIV %d IDF %d ODF %d: VCO %.0f MHz, lane %.1f Mbit/s out of range"
                                   % (ndiv, idf, odf, vco / 1e6, lane / 1e6))
        elif off == 0x404 and value >> 3 & 1:
            if not self.v[0x430] & 1:
                raise EmuError("DSI wrapper enabled without its PLL locked")
            if not self.v[4] & 1 or (self.v[0xA0] & 6) != 6:
                raise EmuError("DSI wrapper enabled before the host (CR.EN) and D-PHY (PCTLR CKE, DEN)")
            if not self.emu.ltdc.v[0x18] & 1:
                raise EmuError("DSI started before the LTDC runs (RM0399: start the host after the LTDC)")
        elif off == 0x70:
            self.wfifo.append(value)
        elif off == 0x6C:
            self.packet(value)
        self.v[off] = value

    def packet(self, hdr):
        if not (self.v[4] & 1 and self.v[0x404] >> 3 & 1):
            raise EmuError("DSI command with the host or wrapper off")
        g = self.emu.gpio[6]
        if g.mode(3) != 1 or not g.out(3):
            raise EmuError("DSI command while the panel is held in reset (PG3 low)")
        if self.reset_release is None:
            raise EmuError("DSI command before the panel's reset line was pulsed")
        if self.ms_since(self.reset_release) < 120:
            raise EmuError("DSI command %.1f ms after the panel reset was released (< 120 ms)"
                           % self.ms_since(self.reset_release))
        dt, lsb, msb = hdr & 0x3F, hdr >> 8 & 0xFF, hdr >> 16 & 0xFF
        if dt == 0x37:
            self.max_return = lsb | msb << 8
            return
        if dt == 0x06:
            if not self.v[0x2C] >> 2 & 1:
                raise EmuError("DCS read without bus turnaround enabled (DSI_PCR.BTAE)")
            if self.max_return < 1:
                raise EmuError("DCS read before a maximum-return-packet-size packet")
            self.rfifo.append(self.ids.get(lsb, 0))
            self.packets.append((dt, bytes([lsb]), self.emu.scs.cyc))
            return
        if dt == 0x05:
            data = bytes([lsb])
        elif dt == 0x15:
            data = bytes([lsb, msb])
        elif dt == 0x39:
            n = lsb | msb << 8
            raw = b"".join(w.to_bytes(4, "little") for w in self.wfifo)
            if len(self.wfifo) != (n + 3) // 4:
                raise EmuError("DCS long write of %d bytes with %d payload words queued" % (n, len(self.wfifo)))
            data = raw[:n]
            self.wfifo = []
        else:
            raise EmuError("DSI packet data type 0x%02x not expected from this board" % dt)
        self.packets.append((dt, data, self.emu.scs.cyc))

    def gpio_changed(self, port, old_odr, new_odr):
        """PG3 is the panel's reset line (active low)."""
        if port != 6:
            return
        was, now = old_odr >> 3 & 1, new_odr >> 3 & 1
        if not now and (was or self.low_since is None):
            self.low_since = self.emu.scs.cyc
        if now and not was:
            if self.low_since is None or self.ms_since(self.low_since) < 0.01:
                raise EmuError("panel reset released without a >= 10 us low pulse")
            self.reset_release = self.emu.scs.cyc


# ---------------------------------------------------------------------------
# USB OTG HS: RM0399 chapter "USB on-the-go high-speed (OTG_HS)" (Synopsys
# DWC2), device mode, FIFO mode, with a scripted host on the other side of
# the ULPI PHY.  Rules: both RCC clocks (core, ULPI) before any access; the
# core out of reset and in device mode with the external PHY before the
# host sees it; every ULPI pin in AF10; received packets popped through
# GRXSTSP with exactly their data words read before the next pop; an
# endpoint receives only while enabled (else the host gets NAK); IN data
# only into an enabled endpoint, no more than its transfer size.
# ---------------------------------------------------------------------------
class Usb(Model):
    name, base, size = "OTG_HS", 0x40040000, 0x40000
    clock = ("AHB1ENR", 25)
    ULPI_PINS = [(0, 3), (0, 5), (1, 0), (1, 1), (1, 5), (1, 10), (1, 11), (1, 12), (1, 13), (2, 0), (7, 4), (8, 11)]
    regs = {0x000: ("GOTGCTL", 0), 0x004: ("GOTGINT", 0), 0x008: ("GAHBCFG", 0), 0x00C: ("GUSBCFG", 0x1440),
            0x010: ("GRSTCTL", 0x80000000), 0x014: ("GINTSTS", 0x04000020), 0x018: ("GINTMSK", 0),
            0x01C: ("GRXSTSR", 0), 0x020: ("GRXSTSP", 0), 0x024: ("GRXFSIZ", 0x200), 0x028: ("DIEPTXF0", 0x2000200),
            0x038: ("GCCFG", 0), 0x03C: ("CID", 0x1200), 0x104: ("DIEPTXF1", 0), 0x108: ("DIEPTXF2", 0),
            0x800: ("DCFG", 0x02200000), 0x804: ("DCTL", 2), 0x808: ("DSTS", 0x10), 0x810: ("DIEPMSK", 0),
            0x814: ("DOEPMSK", 0), 0x818: ("DAINT", 0), 0x81C: ("DAINTMSK", 0), 0x834: ("DIEPEMPMSK", 0),
            0xE00: ("PCGCCTL", 0)}
    for _n in range(4):
        for _o, _r in ((0x900, "DIEPCTL"), (0x908, "DIEPINT"), (0x910, "DIEPTSIZ"), (0x918, "DTXFSTS"),
                       (0xB00, "DOEPCTL"), (0xB08, "DOEPINT"), (0xB10, "DOEPTSIZ")):
            regs[_o + 0x20 * _n] = ("%s%d" % (_r, _n), 0x80 if _r == "DIEPINT" else 0)
    for _n in range(4):
        regs[0x1000 * (_n + 1)] = ("FIFO%d" % _n, 0)

    def __init__(self, emu):
        super().__init__(emu)
        self.rx = []  # (status word, data bytes)
        self.cur = None  # data words left of the popped entry
        self.tx = {0: bytearray(), 1: bytearray()}
        self.sent = {0: [], 1: []}  # completed IN transfers
        self.reset_done = False

    def check_clock(self):
        super().check_clock()
        if not self.emu.rcc.enabled("AHB1ENR", 26):
            raise EmuError("OTG_HS accessed without its ULPI clock (RCC_AHB1ENR.USB1OTGHSULPIEN)")

    def read(self, off):
        if off == 0x14:
            return self.v[0x14] | (0x10 if self.rx else 0)
        if off == 0x20:
            if self.cur:
                raise EmuError("GRXSTSP popped with %d data words of the previous entry unread" % len(self.cur))
            if not self.rx:
                raise EmuError("GRXSTSP popped with the RX FIFO empty")
            st, data = self.rx.pop(0)
            data = bytes(data) + b"\0" * ((-len(data)) % 4)
            self.cur = [int.from_bytes(data[i:i + 4], "little") for i in range(0, len(data), 4)]
            return st
        if off == 0x1000:
            if not self.cur:
                raise EmuError("RX FIFO read beyond the popped entry's byte count")
            return self.cur.pop(0)
        return self.v[off]

    def write(self, off, value):
        if off == 0x10 and value & 1:
            value &= ~1  # core soft reset completes at once
            self.reset_done = True
        if off == 0x10:
            value = (value & ~0x31) | 0x80000000  # flushes complete at once, AHBIDL
        if off == 0x14:  # write 1 to clear
            self.v[0x14] &= ~value
            return
        if off in (0x908, 0x928, 0xB08, 0xB28):
            self.v[off] &= ~value
            return
        if 0x2000 >= off >= 0x1000 and off % 0x1000 == 0:
            ep = off // 0x1000 - 1
            ctl, tsiz = 0x900 + 0x20 * ep, 0x910 + 0x20 * ep
            if not self.v[ctl] >> 31 & 1:
                raise EmuError("TX FIFO %d written while IN endpoint %d is not enabled" % (ep, ep))
            want = self.v[tsiz] & (0x7F if ep == 0 else 0x7FFFF)  # EP0: 7-bit XFRSIZ
            self.tx[ep] += value.to_bytes(4, "little")
            if len(self.tx[ep]) > want + 3:
                raise EmuError("IN endpoint %d: more data pushed than its transfer size %d" % (ep, want))
            if len(self.tx[ep]) >= want:
                self.sent[ep].append(bytes(self.tx[ep][:want]))
                self.tx[ep] = bytearray()
                self.v[ctl] &= ~(1 << 31)
                self.v[0x908 + 0x20 * ep] |= 1  # XFRC
            return
        if off in (0x910, 0xB10) and value & 0x7FFFF > 0x7F:
            raise EmuError("EP0 transfer size %d does not fit DxEPTSIZ0's 7-bit field" % (value & 0x7FFFF))
        if off in (0x900, 0x920) and value >> 31 & 1 and (self.v[0x910 + (off - 0x900)] & 0x7FFFF) == 0:
            # zero-length packet: goes out at once
            ep = (off - 0x900) // 0x20
            self.sent[ep].append(b"")
            self.v[0x908 + 0x20 * ep] |= 1
            value &= ~(1 << 31)
        self.v[off] = value

    # --- the host side ---------------------------------------------------
    def connect_check(self):
        for port, pin in self.ULPI_PINS:
            g = self.emu.gpio[port]
            if g.mode(pin) != 2 or g.af(pin) != 10:
                raise EmuError("ULPI pin P%s%d not in AF10: the PHY is not connected" % ("ABCDEFGHIJK"[port], pin))
        if not self.reset_done or not self.v[0xC] >> 30 & 1 or self.v[0xC] >> 6 & 1 or self.v[0x804] & 2:
            raise EmuError("host sees no HS device: core reset, forced device mode, ULPI PHY and soft connect needed")

    def irq_line(self):
        """The core's interrupt output: GAHBCFG.GINTMSK and a GINTSTS bit
        its GINTMSK bit lets through (RM0399 OTG_HS interrupt hierarchy)."""
        return bool(self.v[0x8] & 1 and self.read(0x14) & self.v[0x18])

    def bus_reset(self):
        self.connect_check()
        self.v[0x14] |= (1 << 12) | (1 << 13)
        self.v[0x808] = 0  # ENUMSPD high speed
        self.emu.interrupts()

    def setup(self, raw):
        if not (self.v[0xB10] >> 29 & 3):
            raise EmuError("SETUP received with EP0 OUT not armed for SETUP (STUPCNT 0)")
        self.rx.append(((6 << 17) | (8 << 4), raw))
        self.rx.append(((4 << 17), b""))
        self.emu.interrupts()

    def out(self, ep, data):
        """One OUT packet; False = NAK (endpoint not enabled)."""
        ctl, tsiz = 0xB00 + 0x20 * ep, 0xB10 + 0x20 * ep
        if not self.v[ctl] >> 31 & 1:
            return False
        if len(data) > (self.v[tsiz] & (0x7F if ep == 0 else 0x7FFFF)):
            raise EmuError("OUT packet of %d bytes larger than EP%d's transfer size" % (len(data), ep))
        if ep and not self.v[ctl] >> 15 & 1:
            raise EmuError("OUT data to EP%d, which is not active (USBAEP)" % ep)
        self.v[ctl] &= ~(1 << 31)
        self.rx.append(((2 << 17) | (len(data) << 4) | ep, data))
        self.rx.append(((3 << 17) | ep, b""))
        self.emu.interrupts()
        return True


# ---------------------------------------------------------------------------
# Cortex-M7 private peripheral bus: SCB, MPU, cache maintenance, DWT
# (ARMv7-M ARM B3.2, Cortex-M7 TRM chapter 4 "System control")
# ---------------------------------------------------------------------------
class Scs(Model):
    name, base, size = "SCS", 0xE0000000, 0x100000
    regs = {0xE0001000: ("DWT_CTRL", 0x40000000), 0xE0001004: ("DWT_CYCCNT", 0), 0xE0001FB0: ("DWT_LAR", 0),
            0xE000E010: ("SYST_CSR", 0), 0xE000ED00: ("CPUID", 0x411FC272), 0xE000ED04: ("ICSR", 0),
            0xE000ED08: ("VTOR", 0), 0xE000ED0C: ("AIRCR", 0xFA050000), 0xE000ED10: ("SCR", 0),
            0xE000ED14: ("CCR", 0x200), 0xE000ED24: ("SHCSR", 0), 0xE000ED28: ("CFSR", 0), 0xE000ED2C: ("HFSR", 0),
            0xE000ED34: ("MMFAR", 0), 0xE000ED38: ("BFAR", 0), 0xE000ED3C: ("AFSR", 0),
            0xE000ED78: ("CLIDR", 0x09000003), 0xE000ED7C: ("CTR", 0x8303C003),
            0xE000ED80: ("CCSIDR", 0), 0xE000ED84: ("CSSELR", 0), 0xE000ED88: ("CPACR", 0),
            0xE000ED90: ("MPU_TYPE", 0x1000), 0xE000ED94: ("MPU_CTRL", 0), 0xE000ED98: ("MPU_RNR", 0),
            0xE000ED9C: ("MPU_RBAR", 0), 0xE000EDA0: ("MPU_RASR", 0), 0xE000EDFC: ("DEMCR", 0),
            0xE000EF50: ("ICIALLU", 0), 0xE000EF5C: ("DCIMVAC", 0), 0xE000EF60: ("DCISW", 0),
            0xE000EF68: ("DCCMVAC", 0), 0xE000EF6C: ("DCCSW", 0), 0xE000EF70: ("DCCIMVAC", 0), 0xE000EF74: ("DCCISW", 0)}
    # NVIC (ARMv7-M ARM B3.4): 150 external interrupts on the STM32H747.
    for _i in range(5):
        regs[0xE000E100 + 4 * _i] = ("NVIC_ISER%d" % _i, 0)
        regs[0xE000E180 + 4 * _i] = ("NVIC_ICER%d" % _i, 0)
    for _i in range(38):
        regs[0xE000E400 + 4 * _i] = ("NVIC_IPR%d" % _i, 0)
    # Cortex-M7 with 16 KiB D-cache (STM32H747): 4 ways x 128 sets x 32 bytes
    # (CCSIDR for CSSELR = 0 data; 0xF00FE019 in the M7 TRM's encoding).
    DC_WAYS, DC_SETS, LINE = 4, 128, 32

    def __init__(self, emu):
        super().__init__(emu)
        self.regs = {k - self.base: v for k, v in Scs.regs.items()}
        self.v = {off: reset for off, (_n, reset) in self.regs.items()}
        self.invalidated = set()
        self.icache_invalidated = False
        self.cleaned = set()
        self.mpu = {}
        self.cyc = 0
        self.cyc_step = 4000  # cycles each DWT_CYCCNT read advances the model's time
        self.reset_requested = False

    def nvic_enabled(self, irq):
        return bool(self.v[0xE100 + 4 * (irq // 32)] >> (irq % 32) & 1)

    def read(self, off):
        if 0xE180 <= off < 0xE194:  # ICERn reads the enabled set too
            return self.v[off - 0x80]
        if off == 0xED80:
            return 0xF00FE019 if self.v[0xED84] == 0 else 0xF01FE019
        if off == 0x1004:
            self.cyc += self.cyc_step
            return self.cyc & 0xFFFFFFFF
        return self.v[off]

    def dcache_on(self):
        return bool(self.v[0xED14] >> 16 & 1)

    def write(self, off, value):
        name = self.regs[off][0]
        if name.startswith("NVIC_ISER"):
            self.v[off] |= value  # write 1 to enable
            return
        if name.startswith("NVIC_ICER"):
            self.v[off - 0x80] &= ~value  # write 1 to disable
            return
        if name == "DCISW":
            self.invalidated.add((value >> 30, value >> 5 & 0x7F))
        elif name == "ICIALLU":
            self.icache_invalidated = True
        elif name in ("DCCMVAC", "DCCIMVAC"):
            self.cleaned.add(value & ~31)
        elif name == "CCR":
            if value >> 16 & 1 and not self.dcache_on():
                missing = self.DC_WAYS * self.DC_SETS - len(self.invalidated)
                if missing:
                    raise EmuError("D-cache enabled with %d set/way lines not invalidated since reset (Cortex-M7 "
                                   "TRM: invalidate the whole D-cache before enabling it)" % missing)
            if value >> 17 & 1 and not (self.v[0xED14] >> 17 & 1) and not self.icache_invalidated:
                raise EmuError("I-cache enabled without ICIALLU first")
        elif name == "MPU_RASR":
            self.mpu[self.v[0xED98]] = (self.v[0xED9C] & ~31, value)
        elif name == "AIRCR":
            if value >> 16 != 0x05FA:
                raise EmuError("AIRCR written without VECTKEY 0x05FA: ignored by the core")
            if value >> 2 & 1:
                self.reset_requested = True
                self.emu.uc.emu_stop()
            value &= 0xFFFF
        self.v[off] = value

    def mpu_attr(self, addr):
        """(cacheable write-back?, region) of the highest enabled MPU region covering addr."""
        if not self.v[0xED94] & 1:
            return None
        best = None
        for rn in sorted(self.mpu):
            base, rasr = self.mpu[rn]
            size = 1 << (((rasr >> 1) & 0x1F) + 1)
            if rasr & 1 and base <= addr < base + size:
                best = (rn, rasr)
        return best

    def check_flip(self, fb, pitch, lines):
        """Before the LTDC scans out fb, every line of it must have been
        cleaned from the D-cache if that memory is write-back cacheable."""
        if not self.dcache_on():
            return
        region = self.mpu_attr(fb)
        if region is None:
            raise EmuError("frame buffer 0x%08x scanned out with the D-cache on and no MPU region: default map"
                           % fb)
        tex, c, b = region[1] >> 19 & 7, region[1] >> 17 & 1, region[1] >> 16 & 1
        if not c:
            return  # non-cacheable or device: the LTDC sees every store
        first, end = fb & ~31, fb + pitch * lines
        missing = [a for a in range(first, end, 32) if a not in self.cleaned]
        if missing:
            raise EmuError("frame buffer 0x%08x flipped with %d of %d cache lines not cleaned (DCCMVAC) since the "
                           "last flip: the LTDC would scan stale SDRAM" % (fb, len(missing), (end - first) // 32))
        self.cleaned = set()
