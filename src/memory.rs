//! The memory a piece of work may take, known before the work: one [`Budget`] for the process,
//! the least of a fixed cap ([`MAX_MEMORY`], 8 GiB), the address space left under the process's
//! limit (`ulimit -v`) and the memory the machine has available. Every estimate of what a piece of
//! work needs (an image, a mesh, a figure, a recorded trace) is compared with it, and a refusal
//! says which of the three bound it, so that the reader knows what to change.
//!
//! The library reads no files: the command line reads `/proc/self/limits`, `/proc/self/status`
//! and `/proc/meminfo` where they exist, gives their text to [`Budget::from_proc`] and sets the
//! process's budget once ([`set_budget`]); without them (another system, the browser) the budget
//! is the cap.

use std::sync::OnceLock;

/// The most memory any one piece of work may need, 8 GiB, whatever the machine offers.
pub const MAX_MEMORY: u64 = 8 << 30;
/// Bytes in a kibibyte, the unit of `/proc/meminfo` and `/proc/self/status`.
const KIB: u64 = 1 << 10;

/// What bounds the [`Budget`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bound {
    /// The fixed cap, [`MAX_MEMORY`].
    Cap,
    /// The address-space limit (`ulimit -v`), less what the process already maps.
    AddressSpace,
    /// The machine's available memory (`MemAvailable`).
    Available,
}

/// How many bytes a piece of work may need, and what set that number.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Budget {
    /// The bytes.
    pub bytes: u64,
    /// What bounds them.
    pub bound: Bound,
}

impl Budget {
    /// The fixed cap alone.
    pub const CAP: Self = Self { bytes: MAX_MEMORY, bound: Bound::Cap };

    /// The least of the cap, the address space left (`Max address space` of `/proc/self/limits`,
    /// soft limit, less `VmSize` of `/proc/self/status`) and `MemAvailable` of `/proc/meminfo`.
    /// A text that is missing or unreadable leaves its bound out.
    #[must_use]
    pub fn from_proc(limits: Option<&str>, status: Option<&str>, meminfo: Option<&str>) -> Self {
        let mut budget = Self::CAP;
        let mut lower = |bytes: Option<u64>, bound: Bound| {
            if let Some(bytes) = bytes.filter(|b| *b < budget.bytes) {
                budget = Self { bytes, bound };
            }
        };
        let address_space = limits.and_then(address_space_limit).map(|limit| {
            let mapped = status.and_then(|s| kib_field(s, "VmSize:")).unwrap_or(0);
            limit.saturating_sub(mapped)
        });
        lower(address_space, Bound::AddressSpace);
        lower(meminfo.and_then(|m| kib_field(m, "MemAvailable:")), Bound::Available);
        budget
    }

    /// The budget as a refusal names it: `the limit of 8 GiB`, `the 1.2 GiB of address space left
    /// under the process's limit (ulimit -v)`, `the 3.4 GiB of memory available`.
    #[must_use]
    pub fn describe(&self) -> String {
        match self.bound {
            Bound::Cap => format!("the limit of {:.0} GiB", gib(self.bytes)),
            Bound::AddressSpace => {
                format!(
                    "the {} of address space left under the process's limit (ulimit -v)",
                    size(self.bytes)
                )
            }
            Bound::Available => format!("the {} of memory available", size(self.bytes)),
        }
    }

    /// Refuses `needed` bytes above the budget: `WHAT needs about X GiB, more than BUDGET: CHANGE`.
    ///
    /// # Errors
    /// That sentence.
    pub fn check(&self, needed: u64, what: &str, change: &str) -> Result<(), String> {
        if needed <= self.bytes {
            return Ok(());
        }
        Err(format!("{what} needs about {}, more than {}: {change}", size(needed), self.describe()))
    }
}

/// The process's budget, set once by the command line from `/proc`.
static BUDGET: OnceLock<Budget> = OnceLock::new();

/// Sets the process's budget (the first call wins; the command line makes it at its start).
pub fn set_budget(budget: Budget) {
    let _ = BUDGET.set(budget);
}

/// The process's budget: the one set, else [`Budget::CAP`].
#[must_use]
pub fn budget() -> Budget {
    BUDGET.get().copied().unwrap_or(Budget::CAP)
}

/// Bytes as GiB, for a message.
#[must_use]
pub fn gib(bytes: u64) -> f64 {
    bytes as f64 / f64::from(1u32 << 30)
}

/// Bytes for a reader: `1.2 GiB` from 1 GiB up, else `340 MiB`.
#[must_use]
pub fn size(bytes: u64) -> String {
    if gib(bytes) >= 1.0 {
        format!("{:.1} GiB", gib(bytes))
    } else {
        format!("{:.0} MiB", bytes as f64 / f64::from(1u32 << 20))
    }
}

/// The soft `Max address space` of `/proc/self/limits`, in bytes (`None` when unlimited).
fn address_space_limit(limits: &str) -> Option<u64> {
    let line = limits.lines().find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..].split_whitespace().next()?.parse().ok()
}

/// A `NAME: N kB` field of `/proc/meminfo` or `/proc/self/status`, in bytes.
fn kib_field(text: &str, name: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with(name))?;
    let kib: u64 = line[name.len()..].split_whitespace().next()?.parse().ok()?;
    Some(kib.saturating_mul(KIB))
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIMITS: &str = "Limit                     Soft Limit           Hard Limit           Units     \n\
        Max data size             unlimited            unlimited            bytes     \n\
        Max address space         2147483648           unlimited            bytes     \n";
    const STATUS: &str = "Name:\twhitted\nVmPeak:\t  200000 kB\nVmSize:\t  524288 kB\n";
    const MEMINFO: &str =
        "MemTotal:       24684084 kB\nMemFree:        20550504 kB\nMemAvailable:    3145728 kB\n";

    #[test]
    fn the_least_of_the_cap_the_address_space_left_and_the_memory_available() {
        assert_eq!(Budget::from_proc(None, None, None), Budget::CAP);
        // 2 GiB of address space, 512 MiB already mapped: 1.5 GiB left, less than 3 GiB available.
        let budget = Budget::from_proc(Some(LIMITS), Some(STATUS), Some(MEMINFO));
        assert_eq!(budget, Budget { bytes: 3 << 29, bound: Bound::AddressSpace });
        assert!(budget.describe().starts_with("the 1.5 GiB of address space left"), "{}", budget.describe());
        // Unlimited: the memory available.
        let unlimited = LIMITS.replace("2147483648 ", "unlimited  ");
        let budget = Budget::from_proc(Some(&unlimited), Some(STATUS), Some(MEMINFO));
        assert_eq!(budget, Budget { bytes: 3 << 30, bound: Bound::Available });
        assert_eq!(budget.describe(), "the 3.0 GiB of memory available");
        // Plenty of both: the cap.
        let plenty = MEMINFO.replace("3145728", "99145728");
        assert_eq!(Budget::from_proc(Some(&unlimited), None, Some(&plenty)), Budget::CAP);
    }

    #[test]
    fn a_refusal_says_the_need_the_budget_and_the_change() {
        assert_eq!(Budget::CAP.check(MAX_MEMORY, "x", "y"), Ok(()));
        assert_eq!(
            Budget::CAP.check(9 << 30, "the mesh", "use a smaller one"),
            Err("the mesh needs about 9.0 GiB, more than the limit of 8 GiB: use a smaller one".to_owned())
        );
        assert_eq!(size(300 << 20), "300 MiB");
    }
}
