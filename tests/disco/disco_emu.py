"""disco_emu.py - runs the linked STM32H747I-DISCO firmware ELF on an emulated
Cortex-M7 (python3-unicorn) against register models of the peripherals.

What is emulated: the M7 core (unicorn's QEMU TCG), the memories of the
RM0399 memory map (flash, DTCM, AXI SRAM, SRAM1-4; the FMC SDRAM window only
once the FMC has run its SDRAM initialisation sequence), and register models
of RCC, PWR, SYSCFG, FLASH, FMC, GPIO A-K, USART1, LTDC, DSI host and the
Cortex-M7 system control space (SCB, MPU, cache maintenance, DWT).

Every peripheral access is recorded (Access list, in program order).  An
access to an address no model knows, a non-word access to a register, an
access to a peripheral whose RCC clock is off, or a write that breaks one of
the order rules of RM0399 (each rule names its section in the model)
raises EmuError and stops the core at that instruction: what real silicon
would do silently (hang, ignore the write, run out of spec) is a test
failure here.

Nothing in here is the firmware's code: the models are written from
RM0399 (STM32H745/747/755/757 reference manual), the Cortex-M7 TRM and the
ARMv7-M ARM; the firmware is the linked ELF, executed instruction by
instruction.
"""
import struct

from unicorn import Uc, UcError, UC_ARCH_ARM, UC_MODE_THUMB, UC_MODE_MCLASS, UC_HOOK_MEM_UNMAPPED, UC_HOOK_MEM_WRITE
from unicorn import UC_PROT_ALL
from unicorn.arm_const import UC_CPU_ARM_CORTEX_M7, UC_ARM_REG_SP, UC_ARM_REG_LR, UC_ARM_REG_PC
from unicorn.arm_const import UC_ARM_REG_R0, UC_ARM_REG_R1, UC_ARM_REG_R2, UC_ARM_REG_R3, UC_ARM_REG_PRIMASK

from disco_models import Rcc, Pwr, Syscfg, Flash, Fmc, Gpio, Usart, Ltdc, Dsi, Scs, Usb, EmuError, PowerLoss

# RM0399 memory map: RAM-like regions.
RAM_REGIONS = [
    ("FLASH", 0x08000000, 2 << 20),
    ("DTCM", 0x20000000, 128 << 10),
    ("AXISRAM", 0x24000000, 512 << 10),
    ("SRAM123", 0x30000000, 288 << 10),
    ("SRAM4", 0x38000000, 64 << 10),
    ("SYSMEM", 0x1FF00000, 128 << 10),  # system memory; the unique device ID at 0x1FF1E800
]
UID = bytes.fromhex("0a1b2c3d4e5f60718293a4b5")
SDRAM_BASE, SDRAM_BYTES = 0xD0000000, 32 << 20
RETURN_MAGIC = 0x3800FF00  # a halfword in SRAM4 the harness stops at (call())
OTG_HS_IRQ = 77  # RM0399 vector table: OTG_HS global interrupt


class Access:
    __slots__ = ("op", "periph", "reg", "off", "value", "pc")

    def __init__(self, op, periph, reg, off, value, pc):
        self.op, self.periph, self.reg, self.off, self.value, self.pc = op, periph, reg, off, value, pc

    def __repr__(self):
        return "%s %s.%s = 0x%08x @pc 0x%08x" % (self.op, self.periph, self.reg, self.value, self.pc)


def read_elf(path):
    """(loadable segments [(paddr, bytes, memsz)], symbols {name: value}, entry) of an ELF32 LE file."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"\x7fELF" or data[4] != 1 or data[5] != 1:
        raise ValueError("%s: not a 32-bit little-endian ELF" % path)
    (entry, phoff, shoff) = struct.unpack_from("<III", data, 0x18)
    (phentsize, phnum, shentsize, shnum, shstrndx) = struct.unpack_from("<HHHHH", data, 0x2A)
    segs = []
    for i in range(phnum):
        p_type, p_off, _vaddr, paddr, filesz, memsz, _fl, _al = struct.unpack_from("<8I", data, phoff + i * phentsize)
        if p_type == 1 and filesz:
            segs.append((paddr, data[p_off:p_off + filesz], memsz))
    sections = [struct.unpack_from("<10I", data, shoff + i * shentsize) for i in range(shnum)]
    syms = {}
    for sh in sections:
        if sh[1] != 2:  # SHT_SYMTAB
            continue
        strtab = sections[sh[6]]
        for j in range(sh[5] // 16):
            st_name, st_value, st_size, st_info, _o, _s = struct.unpack_from("<IIIBBH", data, sh[4] + j * 16)
            end = data.index(b"\0", strtab[4] + st_name)
            name = data[strtab[4] + st_name:end].decode()
            if name and (st_info & 0xF) in (0, 1, 2):
                syms[name] = (st_value, st_size)
    return segs, syms, entry


class Disco:
    """One board: core, memories, peripheral models.  board.run_reset() runs
    Reset_Handler until the frame loop asks the transport for data (or
    stop_at); board.call(name, *args) runs one firmware function."""

    def __init__(self, elf, hse_hz=25000000, supply="smps", panel="otm8009a", rsr=None):
        self.segs, self.syms, self.entry = read_elf(elf)
        self.log = []
        self.error = None
        self.uc = Uc(UC_ARCH_ARM, UC_MODE_THUMB | UC_MODE_MCLASS)
        self.uc.ctl_set_cpu_model(UC_CPU_ARM_CORTEX_M7)
        for _name, base, size in RAM_REGIONS:
            self.uc.mem_map(base, size, UC_PROT_ALL)
        # Erased flash reads all ones; the image goes on top.
        self.uc.mem_write(0x08000000, b"\xff" * (2 << 20))
        for paddr, blob, _memsz in self.segs:
            self.uc.mem_write(paddr, blob)
        self.uc.mem_write(RETURN_MAGIC, b"\x00\xbf\x00\xbf")  # nop; nop
        self.uc.mem_write(0x1FF1E800, UID)
        self.sdram_mapped = False
        self.uc.hook_add(UC_HOOK_MEM_UNMAPPED, self._unmapped)
        self.rcc = Rcc(self, hse_hz, rsr)
        self.pwr = Pwr(self, supply)
        self.flash = Flash(self)
        self.fmc = Fmc(self)
        self.usart1 = Usart(self, "USART1", 0x40011000, ("APB2ENR", 4))
        self.ltdc = Ltdc(self)
        self.dsi = Dsi(self, panel)
        self.scs = Scs(self)
        self.power_lost = False
        self.irqs_taken = 0
        self.uc.hook_add(UC_HOOK_MEM_WRITE, self.flash.mem_write, None, 0x08000000, 0x081FFFFF)
        self.usb = Usb(self)
        self.models = [self.rcc, self.pwr, Syscfg(self), self.flash, self.fmc, self.usart1, self.ltdc, self.dsi, self.scs,
                       self.usb]
        self.gpio = [Gpio(self, port) for port in range(11)]
        self.models += self.gpio
        pages = {}
        for m in self.models:
            for page in range(m.base & ~0xFFF, m.base + m.size, 0x1000):
                pages.setdefault(page, []).append(m)
        for page in sorted(pages):
            self.uc.mmio_map(page, 0x1000, self._mmio_read, page, self._mmio_write, page)
        self.pages = pages

    # --- memory-mapped I/O dispatch -------------------------------------
    def _model_at(self, addr):
        for m in self.pages.get(addr & ~0xFFF, ()):
            if m.base <= addr < m.base + m.size:
                return m
        return None

    def pc(self):
        return self.uc.reg_read(UC_ARM_REG_PC)

    def fail(self, msg):
        if self.error is None:
            self.error = "%s (pc 0x%08x)" % (msg, self.pc())
        self.uc.emu_stop()

    def _mmio_read(self, uc, off, size, page):
        addr = page + off
        m = self._model_at(addr)
        try:
            if m is None:
                raise EmuError("read of 0x%08x: no peripheral register there (RM0399 memory map)" % addr)
            if size != 4 or addr & 3:
                raise EmuError("%d-byte read of %s+0x%x: registers are read as words" % (size, m.name, addr - m.base))
            m.check_clock()
            reg = m.reg_name(addr - m.base)
            value = m.read(addr - m.base) & 0xFFFFFFFF
            self.log.append(Access("R", m.name, reg, addr - m.base, value, self.pc()))
            return value
        except EmuError as e:
            self.fail(str(e))
            return 0

    def _mmio_write(self, uc, off, size, value, page):
        addr = page + off
        m = self._model_at(addr)
        try:
            if m is None:
                raise EmuError("write 0x%x to 0x%08x: no peripheral register there (RM0399 memory map)" % (value, addr))
            if not m.byte_ok(addr - m.base, size) and (size != 4 or addr & 3):
                raise EmuError("%d-byte write to %s+0x%x: registers are written as words" % (size, m.name, addr - m.base))
            m.check_clock()
            reg = m.reg_name(addr - m.base)
            self.log.append(Access("W", m.name, reg, addr - m.base, value & 0xFFFFFFFF, self.pc()))
            m.write(addr - m.base, value & 0xFFFFFFFF)
        except PowerLoss:
            pass  # the core already stopped
        except EmuError as e:
            self.fail(str(e))

    def _unmapped(self, uc, access, addr, size, value, data):
        if SDRAM_BASE <= addr < SDRAM_BASE + SDRAM_BYTES and self.fmc.sdram_ready() and not self.sdram_mapped:
            uc.mem_map(SDRAM_BASE, SDRAM_BYTES, UC_PROT_ALL)
            self.sdram_mapped = True
            return True
        if SDRAM_BASE <= addr < SDRAM_BASE + SDRAM_BYTES:
            self.fail("SDRAM access at 0x%08x before the FMC SDRAM initialisation sequence finished (RM0399 FMC "
                      "'SDRAM initialization')" % addr)
        else:
            self.fail("access to unmapped address 0x%08x (size %d)" % (addr, size))
        return False

    # --- running ---------------------------------------------------------
    def sym(self, name):
        return self.syms[name][0]

    def run(self, begin, until, timeout_s=60):
        try:
            self.uc.emu_start(begin | 1, until, timeout=int(timeout_s * 1e6) if timeout_s else 0)
        except UcError as e:
            if self.error is None:
                self.error = "CPU exception %s at pc 0x%08x" % (e, self.pc())
        if self.error:
            raise EmuError(self.error)
        if self.scs.reset_requested or self.power_lost:
            return  # SYSRESETREQ or power cut: the core stops here
        if self.pc() != until:
            raise EmuError("stopped at pc 0x%08x before reaching 0x%08x (timeout %d s?)" % (self.pc(), until, timeout_s))

    def run_reset(self, stop_at="tdc_board_transport_read", timeout_s=60):
        sp, reset = struct.unpack("<II", bytes(self.uc.mem_read(0x08000000, 8)))
        self.uc.reg_write(UC_ARM_REG_SP, sp)
        self.run(reset & ~1, self.sym(stop_at) & ~1, timeout_s)

    def call(self, name, *args, timeout_s=30):
        regs = [UC_ARM_REG_R0, UC_ARM_REG_R1, UC_ARM_REG_R2, UC_ARM_REG_R3]
        sp = self.uc.reg_read(UC_ARM_REG_SP)
        if sp == 0:
            sp = struct.unpack("<I", bytes(self.uc.mem_read(0x08000000, 4)))[0]
        sp -= 64
        extra = list(args[4:])
        for i, v in enumerate(extra):
            self.uc.mem_write(sp + 4 * i, struct.pack("<I", v & 0xFFFFFFFF))
        self.uc.reg_write(UC_ARM_REG_SP, sp)
        for r, v in zip(regs, args[:4]):
            self.uc.reg_write(r, v & 0xFFFFFFFF)
        self.uc.reg_write(UC_ARM_REG_LR, RETURN_MAGIC | 1)
        self.run(self.sym(name) & ~1, RETURN_MAGIC, timeout_s)
        self.uc.reg_write(UC_ARM_REG_SP, sp + 64)
        r0 = self.uc.reg_read(UC_ARM_REG_R0)
        self.interrupts()  # one the function left pending (e.g. unmasked in the NVIC) is taken on return
        return r0

    def interrupts(self):
        """The OTG_HS interrupt, taken when the DWC2 model asserts it, the
        NVIC has it enabled and PRIMASK is clear: the handler the vector
        table names for position 77 runs (an exception handler is an AAPCS
        function on ARMv7-M; the hardware-stacked frame is not modelled),
        again while the line stays asserted, as the NVIC re-pends a level
        interrupt.  Taken between the harness's steps, never in the middle
        of running code: preemption races are not exercised."""
        for _ in range(64):
            if self.scs.reset_requested or self.power_lost or not self.usb.irq_line():
                return
            if not self.scs.nvic_enabled(OTG_HS_IRQ) or self.uc.reg_read(UC_ARM_REG_PRIMASK) & 1:
                return  # pending; taken once unmasked
            handler = struct.unpack("<I", bytes(self.uc.mem_read(0x08000000 + 4 * (16 + OTG_HS_IRQ), 4)))[0]
            if not handler & 1 or not 0x08000000 <= handler < 0x08200000:
                raise EmuError("OTG_HS interrupt: vector table entry 0x%08x is no Thumb handler in flash" % handler)
            self.irqs_taken += 1
            sp = self.uc.reg_read(UC_ARM_REG_SP) or struct.unpack("<I", bytes(self.uc.mem_read(0x08000000, 4)))[0]
            self.uc.reg_write(UC_ARM_REG_SP, (sp - 128) & ~7)
            self.uc.reg_write(UC_ARM_REG_LR, RETURN_MAGIC | 1)
            self.run(handler & ~1, RETURN_MAGIC, 30)
            self.uc.reg_write(UC_ARM_REG_SP, sp)
        raise EmuError("OTG_HS interrupt still asserted after 64 handler runs: the handler does not clear its cause")

    # --- queries for tests ----------------------------------------------
    def writes(self, periph, reg=None):
        return [a for a in self.log if a.op == "W" and a.periph == periph and (reg is None or a.reg == reg)]

    def last(self, periph, reg):
        w = self.writes(periph, reg)
        return w[-1].value if w else None

    def index(self, pred):
        for i, a in enumerate(self.log):
            if pred(a):
                return i
        return -1

    def uart_text(self):
        return self.usart1.text()
