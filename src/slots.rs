//! Generational slot bookkeeping, shared by the three arenas.
//!
//! Why not `slotmap` (or the archived `generational-arena`)? Those crates
//! store the generation *inside* each value's slot and give every arena its
//! own key space. meshloom needs three things they do not offer together:
//! twin half-edges that share one generation (so `twin` is arithmetic and
//! costs no storage), attribute columns that sit beside the arena and are
//! indexed by the same slot number, and a free list that costs nothing while
//! no element has been removed (a freshly built mesh has none). A built
//! triangle mesh with f64 positions holds about 111 heap bytes per vertex,
//! generations implied (below) and the arrays' 3 % headroom
//! ([`headroom`](crate::layout::headroom)) included.
//!
//! # Generations
//!
//! A slot's generation is odd while it is occupied and even while it is
//! vacant, so a live key always has an odd generation and a scan over
//! `generations` alone tells which slots are live. Freeing a slot and
//! reusing it each add one, so a key kept across a removal no longer
//! matches. Generations only grow and never wrap: a slot whose next
//! generation would pass [`MAX_LIVE_GENERATION`] is retired (left vacant,
//! never reused) instead of wrapping round to an old key. The decisions are
//! compares or checked arithmetic (`reusable`, [`Slots::compacted`],
//! [`Slots::from_generations`]); the increments in `alloc` and `free` then
//! have room by construction (asserted in debug builds).
//!
//! Every arena has a **base** generation (odd, 1 for a built mesh): a new
//! slot at the end starts at the base, and every generation in the arena is
//! at least the base. [`Mesh::compact`](crate::Mesh::compact) moves elements
//! to other slots, so it gives every element a base above every generation
//! the arena ever issued ([`Slots::compacted`]): every key from before is
//! then stale, and only the returned maps give the new ones.
//!
//! # Undo and the fresh floor
//!
//! The journal ([`journal`](crate::journal)) undoes a birth by making the
//! slot vacant one generation *above* the undone element's (never back to
//! the generation it had before), and undoes a death by reviving the slot at
//! the generation its element had. A revived slot may then sit below a
//! generation that an undone later element held; so that no key of an
//! undone element is ever issued again to another element, every arena
//! keeps a **fresh** floor (odd, at least the base): a generation issued by
//! [`Slots::alloc`] (new slot or reused) is never below it, and the journal
//! raises it above every generation a revived slot had reached. While it
//! is above the base the arena is `Mixed`. With no journal it stays at the
//! base and costs one compare in the reuse path.
//!
//! # Fast paths
//!
//! While every live generation equals the base (`pristine`: no slot reused
//! since the arena was built or compacted), making a key for a neighbour
//! needs no load from `generations`, which saves a load per neighbour in
//! one-ring circulation on a freshly built mesh.
//!
//! Likewise, while no slot was freed since then (`intact`), every slot is
//! live at the base, so checking a key is a compare with the base and a
//! bounds test, with no load: reading an attribute by key on a mesh that was
//! loaded and not edited costs what indexing a `Vec` costs. Both paths
//! survive compaction, which leaves every arena pristine and intact at its
//! new base.
//!
//! # Implied generations
//!
//! While an arena is intact every generation is the base, so the arena
//! stores none: `generations` stays empty and `slots` counts the slots. The
//! vector is written out (at the base) the first time a slot is freed or a
//! generation has to differ, and stays written out from then on. A built
//! or compacted mesh thus carries no generation bytes at all: 24 fewer heap
//! bytes per vertex on a triangle mesh (about V + E + F = 6V slots of 4
//! bytes), and the build does not write them.

mod undo;

/// The largest generation a live slot gets. Freeing it gives the even
/// `MAX_LIVE_GENERATION + 1`, which is never reissued.
pub(crate) const MAX_LIVE_GENERATION: u32 = u32::MAX - 2;

/// Generations and the free list of one arena.
#[derive(Debug)]
pub(crate) struct Slots {
    /// One generation per slot, or empty while every generation is
    /// implied (the base; only while `Intact`, see the module docs).
    generations: Vec<u32>,
    /// Slots ever allocated (live or vacant).
    slots: usize,
    free: Vec<u32>,
    live: usize,
    /// Odd; a new slot starts here, and no slot's generation is below it.
    base: u32,
    /// How much is known without reading `generations` (one field, so that
    /// "intact implies pristine" is visible to the optimizer: a key made
    /// and checked in one loop compares the base with itself).
    state: State,
    /// Odd, at least `base`: no generation below it is issued any more
    /// (see the module docs). Equal to `base` until an undo raises it.
    fresh: u32,
}

impl Clone for Slots {
    /// A copy whose written-out generations keep
    /// [`headroom`](crate::layout::headroom) to spare, as the arena
    /// arrays do.
    fn clone(&self) -> Self {
        Slots {
            generations: if self.generations.is_empty() {
                Vec::new()
            } else {
                crate::layout::to_vec_with_headroom(&self.generations)
            },
            slots: self.slots,
            free: self.free.clone(),
            live: self.live,
            base: self.base,
            state: self.state,
            fresh: self.fresh,
        }
    }
}

impl PartialEq for Slots {
    /// Equal when they hold the same slots at the same generations, the
    /// same free list and the same fast-path state, whether or not the
    /// generations are written out.
    fn eq(&self, other: &Self) -> bool {
        self.slots == other.slots
            && self.free == other.free
            && self.live == other.live
            && self.base == other.base
            && self.state == other.state
            && self.fresh == other.fresh
            && (0..self.slots).all(|i| self.generation(i) == other.generation(i))
    }
}

impl Eq for Slots {}

/// What every slot is known to be.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Default)]
pub(crate) enum State {
    /// No slot freed since the arena was built or compacted: every slot is
    /// live at the base generation, so checking a key needs no load.
    #[default]
    Intact,
    /// No slot reused since then: every live slot has the base generation,
    /// so making a key needs no load.
    Pristine,
    /// Generations must be read.
    Mixed,
}

impl Default for Slots {
    fn default() -> Self {
        Slots::empty()
    }
}

impl Slots {
    /// The base of a built arena.
    pub(crate) const FIRST_BASE: u32 = 1;

    /// An empty arena.
    pub(crate) fn empty() -> Self {
        Slots {
            generations: Vec::new(),
            slots: 0,
            free: Vec::new(),
            live: 0,
            base: Self::FIRST_BASE,
            state: State::Intact,
            fresh: Self::FIRST_BASE,
        }
    }

    /// `n` live slots of generation 1, none vacant (a freshly built arena).
    pub(crate) fn full(n: usize) -> Self {
        Self::full_at(n, Self::FIRST_BASE)
    }

    /// `n` live slots at base generation `base` (odd), none vacant.
    fn full_at(n: usize, base: u32) -> Self {
        debug_assert!(base & 1 == 1 && base <= MAX_LIVE_GENERATION);
        Slots {
            generations: Vec::new(),
            slots: n,
            free: Vec::new(),
            live: n,
            base,
            state: State::Intact,
            fresh: base,
        }
    }

    /// Live elements.
    #[inline]
    pub(crate) fn live(&self) -> usize {
        self.live
    }

    /// Slots ever allocated (live or vacant): the length of every column.
    #[inline]
    pub(crate) fn slot_count(&self) -> usize {
        self.slots
    }

    /// Whether the generations are implied (all the base, none stored).
    #[inline]
    fn implied(&self) -> bool {
        self.generations.len() != self.slots
    }

    /// The generations, written out at the base first if they were
    /// implied: every path that changes a generation goes through here.
    fn generations_mut(&mut self) -> &mut Vec<u32> {
        if self.implied() {
            debug_assert!(self.generations.is_empty() && self.state == State::Intact);
            self.generations = crate::layout::filled_with_headroom(self.base, self.slots);
        }
        &mut self.generations
    }

    /// The base generation: every generation in the arena is at least this.
    #[inline]
    pub(crate) fn base(&self) -> u32 {
        self.base
    }

    /// The generation of slot `i`; `None` past the end.
    #[inline]
    pub(crate) fn generation(&self, i: usize) -> Option<u32> {
        if self.implied() {
            (i < self.slots).then_some(self.base)
        } else {
            self.generations.get(i).copied()
        }
    }

    /// The current generation of a slot known to be live.
    #[inline]
    pub(crate) fn generation_of(&self, i: u32) -> u32 {
        if self.pristine() {
            self.base
        } else {
            self.generations[i as usize]
        }
    }

    /// Whether `(index, generation)` names the live element in its slot.
    #[inline]
    pub(crate) fn is_current(&self, index: u32, generation: u32) -> bool {
        if self.state == State::Intact {
            generation == self.base && (index as usize) < self.slots
        } else {
            generation & 1 == 1 && self.generations.get(index as usize) == Some(&generation)
        }
    }

    /// Whether no slot was freed since the arena was built or compacted
    /// (every slot live at the base generation).
    #[inline]
    pub(crate) fn intact(&self) -> bool {
        self.state == State::Intact
    }

    /// Whether no slot was reused since the arena was built or compacted
    /// (every live slot at the base generation).
    #[inline]
    fn pristine(&self) -> bool {
        self.state <= State::Pristine
    }

    /// Which slots of `range` are live, as run lengths alternating live,
    /// vacant, live, ... (the first run may be empty), appended to `runs`.
    /// Reads the generations' parity a run at a time (a tight scan, no
    /// per-slot state test).
    pub(crate) fn live_runs(&self, range: std::ops::Range<u32>, runs: &mut Vec<u32>) {
        let (start, end) = (range.start as usize, range.end as usize);
        if self.state == State::Intact || self.implied() {
            // Every slot below the count is live.
            runs.push((end.min(self.slots).saturating_sub(start)) as u32);
            if end > self.slots {
                runs.push((end - self.slots.max(start)) as u32);
            }
            return;
        }
        // Slots past the generations (none in the journal's ranges) are
        // vacant: scan the part of the range that has generations.
        let have = self.generations.len();
        let gens = &self.generations[start.min(have)..end.min(have)];
        let mut live = true;
        let mut at = 0;
        loop {
            let rest = &gens[at..];
            let run = run_of_parity(rest, u32::from(live));
            runs.push(run as u32);
            at += run;
            if at == gens.len() {
                break;
            }
            live = !live;
        }
        let missing = (end - start) - gens.len();
        if missing > 0 {
            if live {
                runs.push(missing as u32);
            } else if let Some(last) = runs.last_mut() {
                *last += missing as u32;
            }
        }
    }

    /// Whether slot `i` is occupied.
    #[inline]
    pub(crate) fn is_live(&self, i: usize) -> bool {
        if self.state == State::Intact {
            i < self.slots
        } else {
            self.generations.get(i).is_some_and(|g| g & 1 == 1)
        }
    }

    /// Slot `i`'s index and generation, if it is live.
    #[inline]
    pub(crate) fn live_at(&self, i: usize) -> Option<(u32, u32)> {
        let i = u32::try_from(i).ok()?;
        self.is_live(i as usize).then(|| (i, self.generation_of(i)))
    }

    /// Take a slot: a vacant one if any, else a new one at the end (at the
    /// base generation). Returns `(index, generation, is_new)`.
    #[inline]
    pub(crate) fn alloc(&mut self) -> (u32, u32, bool) {
        self.live += 1;
        if let Some(i) = self.free.pop() {
            self.state = State::Mixed;
            let fresh = self.fresh;
            let g = &mut self.generations_mut()[i as usize];
            // The free list holds only slots whose next generation exists
            // (`reusable`, checked when the slot was freed), and `fresh` is
            // at most MAX_LIVE_GENERATION: no overflow. Both are odd.
            *g = (*g + 1).max(fresh);
            debug_assert!(*g & 1 == 1 && *g <= MAX_LIVE_GENERATION);
            (i, *g, false)
        } else {
            let i = u32::try_from(self.slots).expect("more than 2^32 slots");
            if self.implied() {
                // Intact: the fresh floor is the base, which is implied.
                debug_assert!(self.fresh == self.base);
            } else {
                self.generations.push(self.fresh);
            }
            self.slots += 1;
            (i, self.fresh, true)
        }
    }

    /// Vacate slot `i`. Keys to it become stale. A slot whose next
    /// generation would pass [`MAX_LIVE_GENERATION`] is retired instead of
    /// reused, so no key is ever reissued.
    pub(crate) fn free(&mut self, i: u32) {
        self.generations_mut();
        let g = &mut self.generations[i as usize];
        debug_assert!(*g & 1 == 1, "freeing a vacant slot");
        if self.state == State::Intact {
            self.state = State::Pristine;
        }
        // A live generation is at most MAX_LIVE_GENERATION (issued only
        // through `reusable` or a checked base): no overflow.
        debug_assert!(*g <= MAX_LIVE_GENERATION);
        *g += 1;
        self.live -= 1;
        if Self::reusable(*g) {
            self.free.push(i);
        }
    }

    /// Whether a vacant slot of (even) generation `g` may be issued again:
    /// whether `g + 1` is at most [`MAX_LIVE_GENERATION`] (a compare, so
    /// nothing can overflow).
    #[inline]
    fn reusable(g: u32) -> bool {
        g < MAX_LIVE_GENERATION
    }

    /// The live slot indices, in slot order.
    pub(crate) fn live_indices(&self) -> impl Iterator<Item = u32> + '_ {
        let all = if self.implied() { self.slots } else { 0 };
        (0..all as u32).chain(
            self.generations
                .iter()
                .enumerate()
                .filter(|(_, g)| *g & 1 == 1)
                .map(|(i, _)| i as u32),
        )
    }

    /// A copy of this arena with `n` more live slots at the end, at the
    /// fresh floor (where [`alloc`](Self::alloc) puts a new slot), in
    /// one allocation of exactly the size needed. Keys to the existing
    /// slots keep their meaning.
    pub(crate) fn extended(&self, n: usize) -> Slots {
        if self.implied() {
            // Intact, fresh floor at the base: the new slots are implied too.
            let mut s = self.clone();
            s.slots += n;
            s.live += n;
            return s;
        }
        let mut generations = crate::layout::with_headroom(self.generations.len() + n);
        generations.extend_from_slice(&self.generations);
        // New slots get the fresh floor, as `alloc` gives them: after an
        // undo it lies above the base, so no undone key comes back.
        generations.resize(self.generations.len() + n, self.fresh);
        Slots {
            generations,
            slots: self.slots + n,
            free: self.free.clone(),
            live: self.live + n,
            base: self.base,
            state: self.state,
            fresh: self.fresh,
        }
    }

    /// Heap bytes held.
    pub(crate) fn heap_bytes(&self) -> usize {
        (self.generations.capacity() + self.free.capacity()) * 4
    }

    /// The arena after compaction into `live` dense slots: every slot live
    /// at a new base above every generation this arena ever issued (the
    /// largest in `generations`, or below the old base for slots an earlier
    /// compaction dropped), so every earlier key is stale. `None` when that
    /// base would pass [`MAX_LIVE_GENERATION`]: the arena cannot be
    /// compacted without reissuing a generation.
    pub(crate) fn compacted(&self, live: usize) -> Option<Slots> {
        let highest = self.highest_stored();
        // Generations below `fresh` may have been issued to elements an
        // undo took back: the new base is not below it either.
        let above = (highest.max(self.base).checked_add(1)? | 1).max(self.fresh);
        (above <= MAX_LIVE_GENERATION).then(|| Slots::full_at(live, above))
    }

    /// The highest generation any slot holds (0 with no slot).
    fn highest_stored(&self) -> u32 {
        if self.implied() {
            self.base
        } else {
            self.generations.iter().copied().max().unwrap_or(0)
        }
    }

    /// Rebuild from raw generations and the base (deserialization), refusing
    /// what meshloom never issues: a base that is even or past
    /// [`MAX_LIVE_GENERATION`], a live generation past it, or a generation
    /// below the base. Vacant slots are the even ones; those with a next
    /// generation go on the free list, the others stay retired.
    #[cfg(any(feature = "serde", test))]
    pub(crate) fn from_generations(
        generations: Vec<u32>,
        base: u32,
        fresh: u32,
    ) -> Result<Self, String> {
        if base & 1 == 0 || base > MAX_LIVE_GENERATION {
            return Err(format!(
                "base generation {base} is not an odd number up to {MAX_LIVE_GENERATION}"
            ));
        }
        if fresh & 1 == 0 || fresh < base || fresh > MAX_LIVE_GENERATION {
            return Err(format!(
                "fresh generation {fresh} is not an odd number from the base {base} up to {MAX_LIVE_GENERATION}"
            ));
        }
        if let Some((i, g)) = generations
            .iter()
            .enumerate()
            .find(|&(_, &g)| g < base || (g & 1 == 1 && g > MAX_LIVE_GENERATION))
        {
            return Err(if *g < base {
                format!("slot {i} has generation {g}, below the base generation {base}")
            } else {
                format!(
                    "slot {i} has the live generation {g}, past the largest meshloom issues ({MAX_LIVE_GENERATION})"
                )
            });
        }
        let free: Vec<u32> = generations
            .iter()
            .enumerate()
            .filter(|(_, g)| *g & 1 == 0 && Self::reusable(**g))
            .map(|(i, _)| i as u32)
            .rev()
            .collect();
        let live = generations.iter().filter(|g| *g & 1 == 1).count();
        let state = if fresh != base {
            State::Mixed
        } else if generations.iter().all(|&g| g == base) {
            State::Intact
        } else if generations.iter().all(|&g| g & 1 == 0 || g == base) {
            State::Pristine
        } else {
            State::Mixed
        };
        Ok(Slots {
            slots: generations.len(),
            generations,
            free,
            live,
            base,
            state,
            fresh,
        })
    }

    /// The generations, one per slot (serialization), written out.
    #[cfg(any(feature = "serde", test))]
    pub(crate) fn generations(&self) -> std::borrow::Cow<'_, [u32]> {
        if self.implied() {
            std::borrow::Cow::Owned(vec![self.base; self.slots])
        } else {
            std::borrow::Cow::Borrowed(&self.generations)
        }
    }

    /// The stored generations: empty while they are implied (intact).
    pub(crate) fn stored_generations(&self) -> &[u32] {
        &self.generations
    }
}

/// How many leading generations of `gens` have parity `parity` (1: live,
/// 0: vacant). Sixteen at a time while whole blocks match (a branch-free
/// fold the compiler vectorises), then one at a time.
fn run_of_parity(gens: &[u32], parity: u32) -> usize {
    let mut run = 0;
    let mut blocks = gens.chunks_exact(16);
    for block in &mut blocks {
        let mismatched = block.iter().fold(0, |acc, &g| acc | ((g ^ parity) & 1));
        if mismatched != 0 {
            break;
        }
        run += 16;
    }
    run + gens[run..]
        .iter()
        .position(|&g| g & 1 != parity)
        .unwrap_or(gens.len() - run)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reuse_bumps_generation() {
        let mut s = Slots::default();
        let (a, ga, new) = s.alloc();
        assert!(new && s.is_current(a, ga));
        s.free(a);
        assert!(!s.is_current(a, ga));
        assert!(!s.is_live(a as usize));
        let (b, gb, new) = s.alloc();
        assert_eq!((a, false), (b, new));
        assert_ne!(ga, gb);
        assert!(s.is_current(b, gb) && !s.is_current(a, ga));
        assert_eq!(s.live(), 1);
    }

    #[test]
    fn pristine_until_first_reuse() {
        let mut s = Slots::full(3);
        assert_eq!(s.generation_of(2), 1);
        s.free(1);
        assert_eq!(s.generation_of(0), 1);
        let (i, g, _) = s.alloc();
        assert_eq!((i, g), (1, 3));
        assert_eq!(s.generation_of(1), 3);
        assert_eq!(s.generation_of(0), 1);
    }

    #[test]
    fn intact_arena_stores_no_generation() {
        let mut s = Slots::full(1000);
        assert_eq!(s.heap_bytes(), 0);
        assert_eq!(s.slot_count(), 1000);
        assert_eq!(s.generation(999), Some(1));
        assert_eq!(s.generation(1000), None);
        let (i, g, new) = s.alloc();
        assert_eq!((i, g, new), (1000, 1, true));
        assert_eq!(s.heap_bytes(), 0, "a new slot at the base stays implied");
        assert_eq!(s.live_indices().count(), 1001);
        let written = Slots::from_generations(vec![1; 1001], 1, 1).unwrap();
        assert_eq!(
            s, written,
            "implied and written-out generations compare equal"
        );
        s.free(7);
        assert!(s.heap_bytes() >= 1001 * 4, "the first free writes them out");
        assert_eq!(s.generation(7), Some(2));
        assert_eq!(s.generation(8), Some(1));
        assert_eq!(s.live_indices().count(), 1000);
        assert_ne!(s, written);
    }

    #[test]
    fn extending_an_intact_arena_keeps_it_implied() {
        let s = Slots::full(3).extended(2);
        assert_eq!((s.slot_count(), s.live(), s.heap_bytes()), (5, 5, 0));
        assert!(s.intact() && s.is_current(4, 1) && !s.is_current(5, 1));
    }

    #[test]
    fn intact_until_first_free() {
        let mut s = Slots::full(2);
        assert!(s.intact() && s.is_current(1, 1) && !s.is_current(2, 1) && !s.is_current(0, 3));
        s.free(0);
        assert!(!s.intact());
        assert!(!s.is_current(0, 1), "a freed slot's old key is stale");
        assert!(s.is_current(1, 1));
    }

    #[test]
    fn even_generation_never_current() {
        let s = Slots::from_generations(vec![1, 2, 3], 1, 1).unwrap();
        assert!(s.is_current(0, 1));
        assert!(!s.is_current(1, 2));
        assert_eq!(s.live(), 2);
        assert!(!s.is_current(7, 1));
    }

    #[test]
    fn compaction_raises_the_base_above_every_generation() {
        let mut s = Slots::full(3);
        s.free(1);
        let (i, g, _) = s.alloc(); // slot 1 again, generation 3
        assert_eq!((i, g), (1, 3));
        s.free(2); // generation 2: vacant
        let c = s.compacted(2).unwrap();
        assert_eq!(c.base(), 5);
        assert_eq!(*c.generations(), [5, 5]);
        assert!(c.intact() && c.pristine());
        for (i, g) in [(0, 1), (1, 3), (1, 1), (2, 1)] {
            assert!(!c.is_current(i, g), "({i}, {g})");
        }
        assert!(c.is_current(1, 5));
        // A new slot starts at the base, above every key issued before.
        let mut c = c;
        assert_eq!(c.alloc(), (2, 5, true));
    }

    /// `live_runs` as a slot-by-slot scan would give it.
    fn runs_by_scan(s: &Slots, range: std::ops::Range<u32>) -> Vec<u32> {
        let (mut runs, mut live, mut run) = (Vec::new(), true, 0u32);
        for i in range {
            if s.is_live(i as usize) != live {
                runs.push(run);
                run = 0;
                live = !live;
            }
            run += 1;
        }
        runs.push(run);
        runs
    }

    #[test]
    fn live_runs_alternate_from_live() {
        let mut s = Slots::full(10);
        let mut runs = Vec::new();
        s.live_runs(2..10, &mut runs);
        assert_eq!(runs, [8]);
        for i in [0, 3, 4, 9] {
            s.free(i);
        }
        for range in [0..10, 2..10, 3..5, 5..9, 9..10, 4..4] {
            let mut runs = Vec::new();
            s.live_runs(range.clone(), &mut runs);
            assert_eq!(runs, runs_by_scan(&s, range.clone()), "{range:?}");
        }
        let mut runs = Vec::new();
        s.live_runs(0..10, &mut runs);
        assert_eq!(runs, [0, 1, 2, 2, 4, 1]);
        // Runs longer than a block of sixteen, and vacant blocks.
        let mut s = Slots::full(200);
        for i in (0..3).chain(40..42).chain(77..130).chain([199]) {
            s.free(i);
        }
        for range in [0..200, 1..199, 17..33, 40..130, 130..200] {
            let mut runs = Vec::new();
            s.live_runs(range.clone(), &mut runs);
            assert_eq!(runs, runs_by_scan(&s, range.clone()), "{range:?}");
        }
        // Ranges reaching past the slot count: the slots beyond are vacant,
        // intact or not.
        let intact = Slots::full(20);
        for s in [&s, &intact] {
            for range in [150..230, 10..230, 200..210, 250..260] {
                let mut runs = Vec::new();
                s.live_runs(range.clone(), &mut runs);
                assert_eq!(runs, runs_by_scan(s, range.clone()), "{range:?}");
            }
        }
    }

    #[test]
    fn extended_keeps_old_keys_and_adds_live_slots() {
        let mut s = Slots::full(3);
        s.free(1);
        let e = s.extended(2);
        assert_eq!(e.slot_count(), 5);
        assert_eq!(e.live(), 4);
        assert!(e.is_current(0, 1) && !e.is_current(1, 1) && e.is_current(4, 1));
        // The vacant slot is still reusable.
        let mut e = e;
        assert_eq!(e.alloc(), (1, 3, false));
    }

    #[test]
    fn generations_never_wrap() {
        let top = MAX_LIVE_GENERATION;
        let mut s = Slots::from_generations(vec![top, top - 2], 1, 1).unwrap();
        assert!(!s.pristine() && !s.intact());
        s.free(0); // top + 1: retired
        s.free(1); // top - 1: its next generation is top, still reusable
        let (i, g, new) = s.alloc();
        assert_eq!((i, g, new), (1, top, false));
        // Slot 0 is never reissued; a new slot comes at the end.
        let (i, g, new) = s.alloc();
        assert_eq!((i, g, new), (2, 1, true));
        assert!(!s.is_current(0, top));
        // Compaction cannot raise the base past the largest live generation.
        assert!(s.compacted(2).is_none());
    }

    #[test]
    fn undo_primitives_never_reissue_a_key() {
        let mut s = Slots::full(2);
        // Birth of a new slot, undone: vacant above it, held off the list.
        let (i, g, new) = s.alloc();
        assert_eq!((i, g, new), (2, 1, true));
        s.unbirth(i, false);
        s.restore_state(State::Intact);
        assert!(!s.is_current(2, 1) && s.is_current(0, 1));
        assert_eq!(s.state(), State::Pristine, "a vacant slot rules out Intact");
        // Redo: the same key again.
        s.rebirth(i, false);
        assert!(s.is_current(2, 1));
        // Death of slot 0, then its reuse, both undone: slot 0 lives at 1
        // again and the fresh floor keeps the reused key (0, 3) unissued.
        let g0 = s.generation_of(0);
        s.free(0);
        let (j, gj, _) = s.alloc();
        assert_eq!((j, gj), (0, 3));
        s.unbirth(j, true);
        s.undeath(0, g0);
        assert!(s.is_current(0, 1));
        assert!(s.fresh() > 3);
        s.free(0);
        let (k, gk, _) = s.alloc();
        assert_eq!(k, 0);
        assert!(gk > 3, "generation {gk} reissues the undone key (0, 3)");
        // A released slot is reused.
        s.unbirth(2, false);
        s.release(2);
        assert_eq!(s.alloc().0, 2);
    }

    #[test]
    fn compaction_stays_above_the_fresh_floor() {
        let mut s = Slots::full(1);
        s.raise_fresh(9);
        assert_eq!(s.alloc(), (1, 9, true));
        s.free(1);
        assert_eq!(s.compacted(1).unwrap().base(), 11);
        let mut t = Slots::full(2);
        t.free(1);
        t.raise_fresh(7);
        assert_eq!(t.compacted(1).unwrap().base(), 7);
    }

    #[test]
    fn impossible_generations_are_refused() {
        assert!(Slots::from_generations(vec![u32::MAX], 1, 1).is_err());
        assert!(Slots::from_generations(vec![1, 3], 3, 3).is_err());
        assert!(Slots::from_generations(vec![5], 4, 5).is_err());
        assert!(Slots::from_generations(vec![u32::MAX], u32::MAX, u32::MAX).is_err());
        assert!(Slots::from_generations(vec![1], 1, 2).is_err());
        assert!(Slots::from_generations(vec![3], 3, 1).is_err());
        let s = Slots::from_generations(vec![u32::MAX - 1, 7], 7, 7).unwrap();
        assert_eq!(s.live(), 1);
        assert!(
            s.free.is_empty(),
            "a vacant slot at u32::MAX - 1 is retired"
        );
    }
}
