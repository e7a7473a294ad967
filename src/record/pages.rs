//! Copy-on-first-touch snapshots of a link array for the open step.
//!
//! The array is cut into pages of [`PAGE`] slots. The first write in the
//! open step to any slot of a page copies the whole page (its values as
//! the step found them) into the log; every later write to that page costs
//! one load and a compare against a small per-page table. Sealing walks the
//! copied pages in slot order against the live array and hands out the old
//! value of every slot that changed (a page equal to its copy is passed
//! over in one slice compare): no per-write push, no sort of per-slot
//! entries, and the output comes out ascending by slot.
//!
//! Dense edits (an algorithm that touches most of the mesh) then cost about
//! one `memcpy` of the touched pages; sparse edits cost one page per slot
//! written at worst, so they stay proportional to the change.

/// log2 of the slots per page.
const PAGE_SHIFT: u32 = 5;
/// Slots per page: small enough that a sparse edit copies little, large
/// enough that a dense one seldom leaves the fast path.
pub(crate) const PAGE: usize = 1 << PAGE_SHIFT;

/// The old values of the pages the open step wrote.
#[derive(Debug)]
pub(crate) struct PageLog<T> {
    /// Per page: 1 + the ordinal of its copy in `blocks` (0: not copied in
    /// the open step). Grows on demand; cleared entry by entry.
    map: Vec<u32>,
    /// Copied page numbers, in the order they were first written.
    order: Vec<u32>,
    /// [`PAGE`] values per copied page, in `order`'s order, in blocks of
    /// [`BLOCK`] pages (copy `k` is page `k % BLOCK` of block `k / BLOCK`).
    blocks: Vec<Vec<T>>,
    /// Values held in `blocks`.
    len: usize,
}

/// Pages per block of copies (48 KiB of half-edge records). The copies
/// of a dense step come in blocks, not one buffer of the whole array's
/// size: measured on the 250k grid's `journal` row (2026-11-27, one
/// process running every ml_bench workload first), one 18 MB buffer took
/// fresh, page-faulting memory and pushed the mesh's own growth there too
/// (journal on / off 1.31 to 1.62); blocks fit the heap's free space
/// (1.17 to 1.21).
const BLOCK: usize = 128;

impl<T> Default for PageLog<T> {
    fn default() -> Self {
        PageLog {
            map: Vec::new(),
            order: Vec::new(),
            blocks: Vec::new(),
            len: 0,
        }
    }
}

impl<T: Copy> PageLog<T> {
    /// Before a write to slot `i` of `live`: copy its page unless the open
    /// step copied it already. Slots at or above `limit` (born in the open
    /// step) are never saved.
    #[inline(always)]
    pub(crate) fn save(&mut self, i: u32, limit: u32, live: &[T]) {
        if i < limit {
            let p = (i >> PAGE_SHIFT) as usize;
            if self.map.get(p).is_none_or(|&k| k == 0) {
                self.copy_page(p, limit, live);
            }
        }
    }

    /// Copy page `p` of `live` (the slots below `limit`; the rest of the
    /// page is padding, never read).
    #[inline(never)]
    fn copy_page(&mut self, p: usize, limit: u32, live: &[T]) {
        if p >= self.map.len() {
            self.map.resize((p + 1).next_power_of_two(), 0);
        }
        let k = self.order.len();
        if k / BLOCK == self.blocks.len() {
            self.blocks.push(Vec::with_capacity(BLOCK * PAGE));
        }
        self.order.push(p as u32);
        self.map[p] = self.order.len() as u32;
        let start = p << PAGE_SHIFT;
        let end = (start + PAGE).min(limit as usize);
        let block = &mut self.blocks[k / BLOCK];
        block.extend_from_slice(&live[start..end]);
        if end - start < PAGE {
            let pad = live[start];
            block.resize(block.len() + PAGE - (end - start), pad);
        }
        self.len += PAGE;
    }

    /// Whether no page was copied in the open step.
    #[cfg(test)]
    pub(crate) fn is_empty(&self) -> bool {
        self.order.is_empty()
    }

    /// How many slots the copied pages hold (an upper bound on what
    /// [`drain_changed`](Self::drain_changed) hands out).
    #[inline]
    pub(crate) fn saved_slots(&self) -> usize {
        self.len
    }

    /// Hand `f` every saved slot (those below `limit` on the copied pages)
    /// whose value in `live` differs from the value the open step found,
    /// with that old value, ascending by slot, and forget the copies
    /// (capacity stays for the next step). A page equal to its copy is
    /// passed over in one slice compare: a step that puts most values
    /// back (an edit undone by hand) costs a scan, not a call per slot.
    pub(crate) fn drain_changed(&mut self, limit: u32, live: &[T], mut f: impl FnMut(u32, T))
    where
        T: PartialEq,
    {
        if self.order.is_empty() {
            return;
        }
        // The copies stay in touch order; `map` still names each page's.
        self.order.sort_unstable();
        for &p in &self.order {
            let k = self.map[p as usize] as usize - 1;
            self.map[p as usize] = 0;
            let start = (p as usize) << PAGE_SHIFT;
            let n = PAGE.min(limit as usize - start);
            let at = (k % BLOCK) * PAGE;
            let copy = &self.blocks[k / BLOCK][at..at + n];
            let now = &live[start..start + n];
            if copy == now {
                continue;
            }
            for (j, (&old, cur)) in copy.iter().zip(now).enumerate() {
                if old != *cur {
                    f((start + j) as u32, old);
                }
            }
        }
        self.order.clear();
        self.blocks.iter_mut().for_each(Vec::clear);
        self.len = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn oldest_value_of_each_changed_slot_ascending_below_the_limit() {
        let mut live: Vec<u32> = (0..200).collect();
        let limit = 150;
        let mut log = PageLog::default();
        // Writes in a scattered order, some slots twice, some past the limit.
        for &i in &[140u32, 3, 70, 3, 149, 160, 71] {
            log.save(i, limit, &live);
            live[i as usize] += 1000;
        }
        // A slot written back to its old value is not handed out.
        log.save(72, limit, &live);
        let mut out = Vec::new();
        log.drain_changed(limit, &live, |i, old| out.push((i, old)));
        // Each changed slot below the limit, with its value before the
        // first write.
        assert_eq!(out, [(3, 3), (70, 70), (71, 71), (140, 140), (149, 149)]);
        // The log is empty again, and a new step starts afresh.
        assert!(log.is_empty());
        log.save(3, limit, &live);
        live[3] = 7;
        let mut again = Vec::new();
        log.drain_changed(limit, &live, |i, old| again.push((i, old)));
        assert_eq!(again, [(3, 2003)]);
    }

    #[test]
    fn copies_span_several_blocks() {
        let n = (2 * BLOCK + 3) * PAGE + 5;
        let mut live: Vec<u32> = (0..n as u32).collect();
        let limit = n as u32;
        let mut log = PageLog::default();
        // Every page written, last page first, so copies sit out of order
        // across three blocks; one slot per page changes.
        let written: Vec<u32> = (0..n as u32).step_by(PAGE).rev().collect();
        for &i in &written {
            log.save(i, limit, &live);
            live[i as usize] += 1;
        }
        assert_eq!(log.saved_slots(), n.div_ceil(PAGE) * PAGE);
        let mut out = Vec::new();
        log.drain_changed(limit, &live, |i, old| out.push((i, old)));
        let expected: Vec<(u32, u32)> = written.iter().rev().map(|&i| (i, i)).collect();
        assert_eq!(out, expected);
        assert_eq!(log.saved_slots(), 0);
    }
}
