// SPDX-License-Identifier: MIT
// PngWriter: frames encoded on worker threads, renamed into place in submission order.
#include "render/png_file.h"
#include "supermodal/render.h"

#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>

namespace supermodal
{

struct PngWriter::Impl {
    struct Job {
        long long index = 0;
        std::string path;
        Image image;
    };

    PngWriterDef def;
    std::mutex mutex;
    std::condition_variable changed; ///< A job queued, taken or written; an error; stopping.
    std::deque<Job> jobs;
    long long submitted = 0;  ///< Jobs handed to submit().
    long long next_write = 0; ///< The job whose file goes into place next.
    long long files = 0;      ///< Files written.
    std::optional<Error> error;
    bool stopping = false;
    std::vector<std::thread> threads;

    // Encodes outside the lock, then writes when every earlier job is done: files appear in order.
    void run(Job job)
    {
        Result<std::vector<uint8_t>> bytes = encode_png(job.image);
        job.image = Image{};
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return next_write == job.index; });
        if (!error) {
            Status written = bytes ? render::write_complete_file(job.path, *bytes)
                                   : Status(Error{job.path, "", bytes.error().what});
            if (written)
                ++files;
            else
                error = written.error();
        }
        ++next_write;
        changed.notify_all();
    }

    void work()
    {
        for (;;) {
            std::unique_lock lock(mutex);
            changed.wait(lock, [&] { return stopping || !jobs.empty(); });
            if (jobs.empty())
                return; // stopping with nothing left
            Job job = std::move(jobs.front());
            jobs.pop_front();
            changed.notify_all(); // room in the queue
            lock.unlock();
            run(std::move(job));
        }
    }

    Status wait_all()
    {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return next_write == submitted; });
        return error ? Status(*error) : Status{};
    }
};

PngWriter::PngWriter(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}

Result<std::unique_ptr<PngWriter>> PngWriter::create(const PngWriterDef& def)
{
    if (def.threads < 0 || def.threads > 64)
        return Error{"", "threads", "expected 0 to 64, found " + std::to_string(def.threads)};
    if (def.queue < 1 || def.queue > 64)
        return Error{"", "queue", "expected 1 to 64, found " + std::to_string(def.queue)};
    auto impl = std::make_unique<Impl>();
    impl->def = def;
    for (int i = 0; i < def.threads; ++i)
        impl->threads.emplace_back([p = impl.get()] { p->work(); });
    return std::unique_ptr<PngWriter>(new PngWriter(std::move(impl)));
}

PngWriter::~PngWriter()
{
    (void)m_impl->wait_all();
    {
        std::lock_guard lock(m_impl->mutex);
        m_impl->stopping = true;
    }
    m_impl->changed.notify_all();
    for (std::thread& t : m_impl->threads)
        t.join();
}

Status PngWriter::submit(const std::string& path, Image&& image)
{
    Impl& m = *m_impl;
    std::unique_lock lock(m.mutex);
    if (m.error)
        return *m.error;
    Impl::Job job{m.submitted++, path, std::move(image)};
    if (m.threads.empty()) { // no threads: encode and write here
        lock.unlock();
        m.run(std::move(job));
        lock.lock();
        return m.error ? Status(*m.error) : Status{};
    }
    m.changed.wait(lock, [&] { return static_cast<int>(m.jobs.size()) < m.def.queue; });
    m.jobs.push_back(std::move(job));
    m.changed.notify_all();
    return {};
}

Status PngWriter::finish()
{
    return m_impl->wait_all();
}

long long PngWriter::files_written() const
{
    std::lock_guard lock(m_impl->mutex);
    return m_impl->files;
}

} // namespace supermodal
